// Opening the Vulkan loader at run time and filling a Vk function table.
#pragma once

#include <string>

#include "harness/gpu/vk_functions.h"

namespace sdb::gpu {

struct LoaderStatus {
  PFN_vkGetInstanceProcAddr get_instance_proc_addr = nullptr;  // null when unavailable
  std::string reason;  // why it is unavailable, one line; empty when it loaded
};

// The process's Vulkan loader (libvulkan.so.1), opened on first use and never closed, so every
// function pointer taken from it stays valid. Thread-safe; never throws.
const LoaderStatus& vulkan_loader();

// Opens `library` (not cached). vulkan_loader() uses it; tests use it to see the missing-loader path.
LoaderStatus open_loader(const char* library);

// Fills the global entry points (vkCreateInstance, ...). False when the loader lacks one we need.
bool load_global_functions(Vk& vk, PFN_vkGetInstanceProcAddr get_instance_proc_addr);
void load_instance_functions(Vk& vk, VkInstance instance);
void load_device_functions(Vk& vk, VkDevice device);

}  // namespace sdb::gpu
