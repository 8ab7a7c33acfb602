// Internal: instance creation, device enumeration and the choice among devices, shared by
// probe() and Context.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "harness/gpu/device_info.h"
#include "harness/gpu/vk_functions.h"

namespace sdb::gpu {

inline constexpr uint32_t k_min_api_version = VK_API_VERSION_1_1;
inline constexpr const char* k_validation_layer = "VK_LAYER_KHRONOS_validation";

struct InstanceRequest {
  bool validation = false;  // VK_LAYER_KHRONOS_validation, when installed
  bool sync_validation = false;  // its synchronization checks too (VK_EXT_validation_features)
  bool debug_utils = false;  // VK_EXT_debug_utils, for the validation messenger
};

struct InstanceResult {
  VkInstance instance = VK_NULL_HANDLE;
  bool validation = false;  // the layer was found and enabled
  bool debug_utils = false;
  uint32_t api_version = 0;  // what the instance was created for
};

// vk must hold the loader's global functions. Throws Unavailable when the loader is older than
// Vulkan 1.1 or finds no driver, VulkanError for other failures. Loads vk's instance functions.
InstanceResult create_instance(Vk& vk, const InstanceRequest& request);

struct PhysicalDevice {
  VkPhysicalDevice handle = VK_NULL_HANDLE;
  DeviceInfo info;  // info.available: usable by us; else info.reason says why not
  uint32_t queue_family = UINT32_MAX;  // graphics + compute
  uint32_t api_version = 0;  // what we may use: the lower of the device's and the instance's
  std::vector<std::string> extensions;
};

// Every physical device with its facts. Throws VulkanError.
std::vector<PhysicalDevice> list_physical_devices(const Vk& vk, const InstanceResult& instance);

struct DeviceChoice {
  int index = -1;  // into the list; -1 with `reason` when none fits
  std::string reason;
};

// `wanted` (else $SUBDIVBENCH_VK_DEVICE) is a case-insensitive substring of the name; without one,
// the first usable device by type rank: discrete, integrated, virtual, cpu, other.
DeviceChoice choose_device(std::span<const DeviceInfo> devices, std::string_view wanted);

// "no Vulkan device (VK_ICD_FILENAMES=/nonexistent)": names the variables that steer the loader.
std::string no_device_reason(std::string_view detail = {});

}  // namespace sdb::gpu
