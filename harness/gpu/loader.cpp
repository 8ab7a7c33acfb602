#include "harness/gpu/loader.h"

#include <dlfcn.h>

namespace sdb::gpu {

LoaderStatus open_loader(const char* library) {
  LoaderStatus status;
  // RTLD_LOCAL: the loader's symbols stay out of the global namespace, so nothing in the
  // process binds to them by accident.
  void* handle = dlopen(library, RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    status.reason = std::string("no Vulkan loader (") + library + " not found)";
    return status;
  }
  status.get_instance_proc_addr =
      reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(handle, "vkGetInstanceProcAddr"));
  if (!status.get_instance_proc_addr) {
    status.reason = std::string("no Vulkan loader (") + library + " lacks vkGetInstanceProcAddr)";
    dlclose(handle);
  }
  return status;
}

const LoaderStatus& vulkan_loader() {
  static const LoaderStatus status = open_loader("libvulkan.so.1");
  return status;
}

bool load_global_functions(Vk& vk, PFN_vkGetInstanceProcAddr get_instance_proc_addr) {
  vk.vkGetInstanceProcAddr = get_instance_proc_addr;
#define SDB_LOAD(name) vk.name = reinterpret_cast<PFN_##name>(get_instance_proc_addr(VK_NULL_HANDLE, #name));
  SDB_VK_GLOBAL_FUNCTIONS(SDB_LOAD)
#undef SDB_LOAD
  // vkEnumerateInstanceVersion is absent from 1.0 loaders; the caller refuses those.
  return vk.vkCreateInstance && vk.vkEnumerateInstanceLayerProperties && vk.vkEnumerateInstanceExtensionProperties;
}

void load_instance_functions(Vk& vk, VkInstance instance) {
#define SDB_LOAD(name) vk.name = reinterpret_cast<PFN_##name>(vk.vkGetInstanceProcAddr(instance, #name));
  SDB_VK_INSTANCE_FUNCTIONS(SDB_LOAD)
#undef SDB_LOAD
}

void load_device_functions(Vk& vk, VkDevice device) {
#define SDB_LOAD(name) vk.name = reinterpret_cast<PFN_##name>(vk.vkGetDeviceProcAddr(device, #name));
  SDB_VK_DEVICE_FUNCTIONS(SDB_LOAD)
#undef SDB_LOAD
}

}  // namespace sdb::gpu
