#include "harness/gpu/physical_device.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>

#include "harness/gpu/errors.h"
#include "harness/gpu/loader.h"

namespace sdb::gpu {

namespace {

std::string version_string(uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
         std::to_string(VK_API_VERSION_PATCH(v));
}

// Vendors pack driverVersion differently; NVIDIA uses 10.8.8.6 bits, most others the API layout.
std::string driver_version_string(uint32_t vendor_id, uint32_t v) {
  if (vendor_id == 0x10DE)
    return std::to_string((v >> 22) & 0x3ff) + "." + std::to_string((v >> 14) & 0xff) + "." +
           std::to_string((v >> 6) & 0xff) + "." + std::to_string(v & 0x3f);
  return version_string(v);
}

std::string vendor_name(uint32_t id) {
  switch (id) {
    case 0x1002: return "AMD";
    case 0x1010: return "ImgTec";
    case 0x106B: return "Apple";
    case 0x10DE: return "NVIDIA";
    case 0x13B5: return "ARM";
    case 0x5143: return "Qualcomm";
    case 0x8086: return "Intel";
    case VK_VENDOR_ID_MESA: return "Mesa";
    default: break;
  }
  char hex[16];
  std::snprintf(hex, sizeof hex, "0x%X", id);
  return hex;
}

DeviceType device_type(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return DeviceType::Integrated;
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return DeviceType::Discrete;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return DeviceType::Virtual;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return DeviceType::Cpu;
    default: return DeviceType::Other;
  }
}

int type_rank(DeviceType t) {
  switch (t) {
    case DeviceType::Discrete: return 0;
    case DeviceType::Integrated: return 1;
    case DeviceType::Virtual: return 2;
    case DeviceType::Cpu: return 3;
    case DeviceType::Other: return 4;
  }
  return 5;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

bool has_layer(const Vk& vk, const char* name) {
  uint32_t count = 0;
  if (vk.vkEnumerateInstanceLayerProperties(&count, nullptr) < 0) return false;
  std::vector<VkLayerProperties> layers(count);
  if (vk.vkEnumerateInstanceLayerProperties(&count, layers.data()) < 0) return false;
  return std::any_of(layers.begin(), layers.begin() + count,
                     [&](const VkLayerProperties& l) { return std::string_view(l.layerName) == name; });
}

bool has_instance_extension(const Vk& vk, const char* layer, const char* name) {
  uint32_t count = 0;
  if (vk.vkEnumerateInstanceExtensionProperties(layer, &count, nullptr) < 0) return false;
  std::vector<VkExtensionProperties> exts(count);
  if (vk.vkEnumerateInstanceExtensionProperties(layer, &count, exts.data()) < 0) return false;
  return std::any_of(exts.begin(), exts.begin() + count,
                     [&](const VkExtensionProperties& e) { return std::string_view(e.extensionName) == name; });
}

std::vector<std::string> device_extensions(const Vk& vk, VkPhysicalDevice pd) {
  uint32_t count = 0;
  check(vk.vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, nullptr), "vkEnumerateDeviceExtensionProperties",
        "listing device extensions");
  std::vector<VkExtensionProperties> exts(count);
  check(vk.vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, exts.data()),
        "vkEnumerateDeviceExtensionProperties", "listing device extensions");
  std::vector<std::string> names;
  for (uint32_t i = 0; i < count; ++i) names.emplace_back(exts[i].extensionName);
  return names;
}

void fill_limits(const VkPhysicalDeviceLimits& l, DeviceLimits& out) {
  out.max_storage_buffer_range = l.maxStorageBufferRange;
  out.max_uniform_buffer_range = l.maxUniformBufferRange;
  out.min_storage_buffer_offset_alignment = std::max<uint64_t>(1, l.minStorageBufferOffsetAlignment);
  out.min_uniform_buffer_offset_alignment = std::max<uint64_t>(1, l.minUniformBufferOffsetAlignment);
  out.max_texel_buffer_elements = l.maxTexelBufferElements;
  out.min_texel_buffer_offset_alignment = std::max<uint64_t>(1, l.minTexelBufferOffsetAlignment);
  for (int i = 0; i < 3; ++i) {
    out.max_compute_work_group_count[i] = l.maxComputeWorkGroupCount[i];
    out.max_compute_work_group_size[i] = l.maxComputeWorkGroupSize[i];
  }
  out.max_compute_work_group_invocations = l.maxComputeWorkGroupInvocations;
  out.max_push_constants_size = l.maxPushConstantsSize;
  out.max_per_stage_storage_buffers = l.maxPerStageDescriptorStorageBuffers;
  out.max_geometry_output_vertices = l.maxGeometryOutputVertices;
  out.max_geometry_total_output_components = l.maxGeometryTotalOutputComponents;
  out.max_tessellation_generation_level = l.maxTessellationGenerationLevel;
  out.max_tessellation_patch_size = l.maxTessellationPatchSize;
  out.max_framebuffer_width = l.maxFramebufferWidth;
  out.max_framebuffer_height = l.maxFramebufferHeight;
  out.timestamp_period_ns = l.timestampPeriod;
  out.timestamp_compute_and_graphics = l.timestampComputeAndGraphics == VK_TRUE;
}

// Properties and features that need the *2 queries (Vulkan 1.1+ devices only).
void fill_extended(const Vk& vk, PhysicalDevice& pd) {
  DeviceInfo& info = pd.info;
  const uint32_t api = pd.api_version;
  const bool has_mesh_ext =
      std::find(pd.extensions.begin(), pd.extensions.end(), VK_EXT_MESH_SHADER_EXTENSION_NAME) != pd.extensions.end();

  // maxMemoryAllocationSize is Vulkan 1.1 (maintenance3), the driver's name 1.2, maxBufferSize 1.3.
  VkPhysicalDeviceMaintenance3Properties maintenance3{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceMaintenance4Properties maintenance4{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_PROPERTIES};
  VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &maintenance3};
  maintenance3.pNext = &subgroup;
  void** next = &subgroup.pNext;
  if (api >= VK_API_VERSION_1_2) {
    *next = &driver;
    next = &driver.pNext;
  }
  if (api >= VK_API_VERSION_1_3) {
    *next = &maintenance4;
    next = &maintenance4.pNext;
  }
  vk.vkGetPhysicalDeviceProperties2(pd.handle, &props2);
  info.limits.max_memory_allocation_size = maintenance3.maxMemoryAllocationSize;
  info.limits.subgroup_size = std::max<uint32_t>(1, subgroup.subgroupSize);
  if (api >= VK_API_VERSION_1_2) {
    info.driver_name = driver.driverName;
    info.driver_info = driver.driverInfo;
  }
  info.limits.max_buffer_size =
      api >= VK_API_VERSION_1_3 ? maintenance4.maxBufferSize : info.limits.max_memory_allocation_size;

  VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceMeshShaderFeaturesEXT mesh{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MESH_SHADER_FEATURES_EXT};
  VkPhysicalDeviceFeatures2 feats2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  next = &feats2.pNext;
  if (api >= VK_API_VERSION_1_2) {
    *next = &v12;
    next = &v12.pNext;
  }
  if (has_mesh_ext) {
    *next = &mesh;
    next = &mesh.pNext;
  }
  vk.vkGetPhysicalDeviceFeatures2(pd.handle, &feats2);
  const VkPhysicalDeviceFeatures& f = feats2.features;
  info.features.geometry_shader = f.geometryShader;
  info.features.tessellation_shader = f.tessellationShader;
  info.features.fill_mode_non_solid = f.fillModeNonSolid;
  info.features.shader_float64 = f.shaderFloat64;
  info.features.shader_int64 = f.shaderInt64;
  info.features.vertex_pipeline_stores_and_atomics = f.vertexPipelineStoresAndAtomics;
  info.features.scalar_block_layout = api >= VK_API_VERSION_1_2 && v12.scalarBlockLayout;
  info.features.mesh_shader = has_mesh_ext && mesh.meshShader;
}

void fill_queue_family(const Vk& vk, PhysicalDevice& pd) {
  uint32_t count = 0;
  vk.vkGetPhysicalDeviceQueueFamilyProperties(pd.handle, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vk.vkGetPhysicalDeviceQueueFamilyProperties(pd.handle, &count, families.data());
  const VkQueueFlags wanted = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  for (uint32_t i = 0; i < count; ++i) {
    if ((families[i].queueFlags & wanted) == wanted && families[i].queueCount > 0) {
      pd.queue_family = i;
      pd.info.limits.timestamp_valid_bits = families[i].timestampValidBits;
      return;
    }
  }
}

PhysicalDevice describe_physical_device(const Vk& vk, VkPhysicalDevice handle, uint32_t instance_api) {
  PhysicalDevice pd;
  pd.handle = handle;
  DeviceInfo& info = pd.info;
  VkPhysicalDeviceProperties props;
  vk.vkGetPhysicalDeviceProperties(handle, &props);
  info.name = props.deviceName;
  info.type = device_type(props.deviceType);
  info.vendor_id = props.vendorID;
  info.device_id = props.deviceID;
  info.vendor = vendor_name(props.vendorID);
  info.driver_version = driver_version_string(props.vendorID, props.driverVersion);
  info.api_version_raw = props.apiVersion;
  info.api_version = version_string(props.apiVersion);
  pd.api_version = std::min(props.apiVersion, instance_api);
  fill_limits(props.limits, info.limits);

  VkPhysicalDeviceMemoryProperties mem;
  vk.vkGetPhysicalDeviceMemoryProperties(handle, &mem);
  for (uint32_t h = 0; h < mem.memoryHeapCount; ++h)
    if (mem.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
      info.limits.device_local_bytes = std::max<uint64_t>(info.limits.device_local_bytes, mem.memoryHeaps[h].size);

  if (pd.api_version < k_min_api_version) {
    info.reason = info.name + " supports Vulkan " + info.api_version + " only; 1.1 is needed";
    return pd;
  }
  pd.extensions = device_extensions(vk, handle);
  fill_extended(vk, pd);
  fill_queue_family(vk, pd);
  if (pd.queue_family == UINT32_MAX) {
    info.reason = info.name + " has no queue family with both graphics and compute";
    return pd;
  }
  info.available = true;
  return pd;
}

}  // namespace

std::string no_device_reason(std::string_view detail) {
  std::string steer;
  for (const char* var : {"VK_ICD_FILENAMES", "VK_DRIVER_FILES", "VK_ADD_DRIVER_FILES", k_device_env}) {
    if (const char* value = std::getenv(var)) {
      steer += steer.empty() ? "" : ", ";
      steer += std::string(var) + "=" + value;
    }
  }
  std::string reason = "no Vulkan device (" + steer;
  if (!detail.empty()) reason += std::string(steer.empty() ? "" : "; ") + std::string(detail);
  if (steer.empty() && detail.empty()) reason += "the loader found no driver";
  return reason + ")";
}

InstanceResult create_instance(Vk& vk, const InstanceRequest& request) {
  uint32_t loader_version = VK_API_VERSION_1_0;
  if (vk.vkEnumerateInstanceVersion) vk.vkEnumerateInstanceVersion(&loader_version);
  if (loader_version < k_min_api_version)
    throw Unavailable("Vulkan loader supports " + version_string(loader_version) + " only; 1.1 is needed");

  InstanceResult result;
  result.api_version = std::min<uint32_t>(loader_version, VK_API_VERSION_1_3);
  std::vector<const char*> layers, extensions;
  result.validation = request.validation && has_layer(vk, k_validation_layer);
  if (result.validation) layers.push_back(k_validation_layer);
  result.debug_utils = request.debug_utils && (has_instance_extension(vk, nullptr, VK_EXT_DEBUG_UTILS_EXTENSION_NAME) ||
                                               (result.validation && has_instance_extension(vk, k_validation_layer,
                                                                                            VK_EXT_DEBUG_UTILS_EXTENSION_NAME)));
  if (result.debug_utils) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  const bool sync = result.validation && request.sync_validation &&
                    has_instance_extension(vk, k_validation_layer, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
  if (sync) extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);

  const VkValidationFeatureEnableEXT sync_feature = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = &sync_feature;

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "subdivbench";
  app.pEngineName = "subdivbench";
  app.apiVersion = result.api_version;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pNext = sync ? &features : nullptr;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = static_cast<uint32_t>(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  VkResult r = vk.vkCreateInstance(&info, nullptr, &result.instance);
  // The loader answers VK_ERROR_INCOMPATIBLE_DRIVER when it finds no driver at all.
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER) throw Unavailable(no_device_reason("vkCreateInstance: VK_ERROR_INCOMPATIBLE_DRIVER"));
  check(r, "vkCreateInstance", "creating the Vulkan instance");
  load_instance_functions(vk, result.instance);
  return result;
}

std::vector<PhysicalDevice> list_physical_devices(const Vk& vk, const InstanceResult& instance) {
  uint32_t count = 0;
  VkResult r = vk.vkEnumeratePhysicalDevices(instance.instance, &count, nullptr);
  if (r == VK_ERROR_INITIALIZATION_FAILED) return {};  // the loader says so when no driver loads
  check(r, "vkEnumeratePhysicalDevices", "listing devices");
  std::vector<VkPhysicalDevice> handles(count);
  r = vk.vkEnumeratePhysicalDevices(instance.instance, &count, handles.data());
  check(r, "vkEnumeratePhysicalDevices", "listing devices");
  std::vector<PhysicalDevice> devices;
  for (uint32_t i = 0; i < count; ++i) devices.push_back(describe_physical_device(vk, handles[i], instance.api_version));
  for (PhysicalDevice& d : devices)
    for (const PhysicalDevice& other : devices)
      d.info.devices.push_back(other.info.name + " (" + std::string(to_string(other.info.type)) + ")");
  return devices;
}

DeviceChoice choose_device(std::span<const DeviceInfo> devices, std::string_view wanted) {
  std::string wanted_name(wanted);
  if (wanted_name.empty())
    if (const char* env = std::getenv(k_device_env)) wanted_name = env;
  DeviceChoice choice;
  if (devices.empty()) {
    choice.reason = no_device_reason();
    return choice;
  }
  if (!wanted_name.empty()) {
    const std::string needle = lower(wanted_name);
    std::string unusable;
    for (size_t i = 0; i < devices.size(); ++i) {
      if (lower(devices[i].name).find(needle) == std::string::npos) continue;
      if (devices[i].available) {
        choice.index = static_cast<int>(i);
        return choice;
      }
      unusable = devices[i].reason;
    }
    std::string names;
    for (const DeviceInfo& d : devices) names += (names.empty() ? "" : ", ") + d.name;
    choice.reason = unusable.empty() ? "no Vulkan device matches '" + wanted_name + "' (devices: " + names + ")"
                                     : "the Vulkan device matching '" + wanted_name + "' is unusable: " + unusable;
    return choice;
  }
  for (size_t i = 0; i < devices.size(); ++i) {
    if (!devices[i].available) continue;
    if (choice.index < 0 || type_rank(devices[i].type) < type_rank(devices[choice.index].type))
      choice.index = static_cast<int>(i);
  }
  if (choice.index < 0) choice.reason = "no usable Vulkan device: " + devices.front().reason;
  return choice;
}

}  // namespace sdb::gpu
