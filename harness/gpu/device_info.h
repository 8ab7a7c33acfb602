// What the Vulkan backend knows about a device before using it: probe() and the plain structs
// it fills. probe() never throws and costs one instance creation (no device is created).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sdb::gpu {

enum class DeviceType { Other, Integrated, Discrete, Virtual, Cpu };
std::string_view to_string(DeviceType type);  // "discrete", "integrated", "virtual", "cpu", "other"

// The limits schemes plan against. Always read them from the chosen device; lavapipe's are not
// everybody's (its 128 MiB maxStorageBufferRange is the common trap).
struct DeviceLimits {
  uint64_t max_storage_buffer_range = 0;  // bytes one storage-buffer binding may cover
  uint64_t max_uniform_buffer_range = 0;
  uint64_t max_memory_allocation_size = 0;  // bytes of one allocation, hence of one of our buffers
  uint64_t max_buffer_size = 0;  // Vulkan 1.3 maxBufferSize; max_memory_allocation_size when not reported
  uint64_t min_storage_buffer_offset_alignment = 1;
  uint64_t min_uniform_buffer_offset_alignment = 1;
  uint64_t max_texel_buffer_elements = 0;  // texels one texel-buffer view may cover
  uint64_t min_texel_buffer_offset_alignment = 1;
  uint64_t device_local_bytes = 0;  // size of the largest device-local heap
  std::array<uint32_t, 3> max_compute_work_group_count{};
  std::array<uint32_t, 3> max_compute_work_group_size{};
  uint32_t max_compute_work_group_invocations = 0;
  uint32_t max_push_constants_size = 0;
  uint32_t subgroup_size = 1;  // invocations that run in lock step (lavapipe: its SIMD width, 8 at 256 bits)
  uint32_t max_per_stage_storage_buffers = 0;
  uint32_t max_geometry_output_vertices = 0;
  uint32_t max_geometry_total_output_components = 0;
  uint32_t max_tessellation_generation_level = 0;
  uint32_t max_tessellation_patch_size = 0;
  uint32_t max_framebuffer_width = 0;
  uint32_t max_framebuffer_height = 0;
  float timestamp_period_ns = 0.0f;  // nanoseconds per timestamp tick
  bool timestamp_compute_and_graphics = false;  // every graphics and compute queue has timestamps
  uint32_t timestamp_valid_bits = 0;  // of the queue family we use; 0: no timestamps there
};

struct DeviceFeatures {
  bool geometry_shader = false;
  bool tessellation_shader = false;
  bool mesh_shader = false;  // VK_EXT_mesh_shader with its meshShader feature
  bool fill_mode_non_solid = false;  // wireframe
  bool shader_float64 = false;
  bool shader_int64 = false;
  bool scalar_block_layout = false;  // GL_EXT_scalar_block_layout: vec3 arrays with a 12-byte stride
  bool vertex_pipeline_stores_and_atomics = false;
};

struct DeviceInfo {
  bool available = false;
  std::string reason;  // one line, when !available

  std::string name;  // "llvmpipe (LLVM 15.0.6, 256 bits)"
  DeviceType type = DeviceType::Other;
  uint32_t vendor_id = 0;
  uint32_t device_id = 0;
  std::string vendor;  // "NVIDIA", "AMD", "Intel", "Mesa", ... or the id in hex
  std::string driver_name;  // "llvmpipe", "NVIDIA" (VkPhysicalDeviceDriverProperties)
  std::string driver_info;  // "Mesa 22.3.6 (LLVM 15.0.6)", "535.104.05"
  std::string driver_version;  // decoded by the vendor's scheme, e.g. "535.104.5.0", "0.0.1"
  std::string api_version;  // "1.3.230"
  uint32_t api_version_raw = 0;
  DeviceFeatures features;
  DeviceLimits limits;

  // Every device the loader reported, "name (type)", the chosen one included; for messages.
  std::vector<std::string> devices;
};

// Environment variables that steer device choice.
inline constexpr const char* k_device_env = "SUBDIVBENCH_VK_DEVICE";  // name substring, case-insensitive

// Finds the device a Context would use: `device_name` (a case-insensitive substring of the device
// name), else $SUBDIVBENCH_VK_DEVICE, else the first usable discrete GPU, then integrated GPU,
// then virtual GPU, then CPU device (lavapipe). A device is usable with Vulkan 1.1 and a queue
// family that does graphics and compute.
DeviceInfo probe(std::string_view device_name = {});

// One line for `subdivbench list backends`: "llvmpipe (LLVM 15.0.6, 256 bits), cpu, Mesa 22.3.6 ..., Vulkan 1.3.230",
// or the reason when unavailable.
std::string summary(const DeviceInfo& info);
// Several "key: value" lines: device, driver, API, the shader stages and limits schemes depend on.
std::string describe(const DeviceInfo& info);

}  // namespace sdb::gpu
