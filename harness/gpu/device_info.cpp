#include "harness/gpu/device_info.h"

#include <cstdio>
#include <exception>

#include "harness/gpu/errors.h"
#include "harness/gpu/loader.h"
#include "harness/gpu/physical_device.h"

namespace sdb::gpu {

std::string_view to_string(DeviceType type) {
  switch (type) {
    case DeviceType::Discrete: return "discrete";
    case DeviceType::Integrated: return "integrated";
    case DeviceType::Virtual: return "virtual";
    case DeviceType::Cpu: return "cpu";
    case DeviceType::Other: return "other";
  }
  return "other";
}

namespace {

// Destroys the probe's instance on every path out.
struct ScopedInstance {
  const Vk& vk;
  VkInstance instance;
  ~ScopedInstance() {
    if (instance && vk.vkDestroyInstance) vk.vkDestroyInstance(instance, nullptr);
  }
};

DeviceInfo probe_or_throw(std::string_view wanted) {
  DeviceInfo out;
  const LoaderStatus& loader = vulkan_loader();
  if (!loader.get_instance_proc_addr) {
    out.reason = loader.reason;
    return out;
  }
  Vk vk;
  if (!load_global_functions(vk, loader.get_instance_proc_addr)) {
    out.reason = "no Vulkan loader (libvulkan.so.1 lacks vkCreateInstance)";
    return out;
  }
  const InstanceResult instance = create_instance(vk, {});
  ScopedInstance scoped{vk, instance.instance};
  std::vector<DeviceInfo> infos;
  for (PhysicalDevice& d : list_physical_devices(vk, instance)) infos.push_back(std::move(d.info));
  DeviceChoice choice = choose_device(infos, wanted);
  if (choice.index < 0) {
    out.reason = choice.reason;
    if (!infos.empty()) out.devices = infos.front().devices;
    return out;
  }
  return infos[choice.index];
}

std::string mib(uint64_t bytes) {
  char text[32];
  if (bytes >= (uint64_t(1) << 30))
    std::snprintf(text, sizeof text, "%.2f GiB", double(bytes) / double(uint64_t(1) << 30));
  else
    std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / double(1 << 20));
  return text;
}

const char* yes_no(bool b) { return b ? "yes" : "no"; }

}  // namespace

DeviceInfo probe(std::string_view device_name) {
  try {
    return probe_or_throw(device_name);
  } catch (const std::exception& e) {
    DeviceInfo out;
    out.reason = e.what();
    return out;
  } catch (...) {
    DeviceInfo out;
    out.reason = "Vulkan probe failed with an unknown exception";
    return out;
  }
}

std::string summary(const DeviceInfo& info) {
  if (!info.available) return info.reason;
  std::string s = info.name + ", " + std::string(to_string(info.type)) + ", ";
  s += info.driver_info.empty() ? info.driver_name + " " + info.driver_version : info.driver_info;
  return s + ", Vulkan " + info.api_version;
}

std::string describe(const DeviceInfo& info) {
  if (!info.available) return "available: no\nreason: " + info.reason + "\n";
  const DeviceLimits& l = info.limits;
  const DeviceFeatures& f = info.features;
  char vendor_id[16];
  std::snprintf(vendor_id, sizeof vendor_id, "0x%X", info.vendor_id);
  std::string s;
  auto line = [&](const char* key, const std::string& value) { s += std::string(key) + ": " + value + "\n"; };
  line("available", "yes");
  line("device", info.name);
  line("type", std::string(to_string(info.type)));
  line("vendor", info.vendor + " (" + vendor_id + ")");
  line("driver", info.driver_name + ", " + info.driver_info + ", version " + info.driver_version);
  line("api", info.api_version);
  line("geometry shader", std::string(yes_no(f.geometry_shader)) + " (max output vertices " +
                              std::to_string(l.max_geometry_output_vertices) + ", max total output components " +
                              std::to_string(l.max_geometry_total_output_components) + ")");
  line("tessellation shader", std::string(yes_no(f.tessellation_shader)) + " (max generation level " +
                                  std::to_string(l.max_tessellation_generation_level) + ", max patch size " +
                                  std::to_string(l.max_tessellation_patch_size) + ")");
  line("mesh shader", yes_no(f.mesh_shader));
  line("max storage buffer range", mib(l.max_storage_buffer_range));
  line("max memory allocation", mib(l.max_memory_allocation_size));
  line("max buffer size", mib(l.max_buffer_size));
  line("device-local heap", mib(l.device_local_bytes));
  line("max compute work groups", std::to_string(l.max_compute_work_group_count[0]) + " x " +
                                      std::to_string(l.max_compute_work_group_count[1]) + " x " +
                                      std::to_string(l.max_compute_work_group_count[2]) + ", " +
                                      std::to_string(l.max_compute_work_group_invocations) + " invocations");
  char period[64];
  std::snprintf(period, sizeof period, "%g ns per tick, %u valid bits", double(l.timestamp_period_ns),
                l.timestamp_valid_bits);
  line("timestamps", std::string(yes_no(l.timestamp_valid_bits > 0)) + " (" + period +
                         ", all graphics+compute queues: " + yes_no(l.timestamp_compute_and_graphics) + ")");
  std::string devices;
  for (const std::string& d : info.devices) devices += (devices.empty() ? "" : "; ") + d;
  line("devices", devices);
  return s;
}

}  // namespace sdb::gpu
