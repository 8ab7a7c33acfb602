#include "harness/gpu/errors.h"

namespace sdb::gpu {

namespace {
std::string message(VkResult result, std::string_view call, std::string_view doing) {
  std::string m(call);
  m += " failed with ";
  m += to_string(result);
  if (!doing.empty()) {
    m += " while ";
    m += doing;
  }
  return m;
}
}  // namespace

VulkanError::VulkanError(VkResult result, std::string_view call, std::string_view doing)
    : std::runtime_error(message(result, call, doing)), result_(result) {}

std::string to_string(VkResult result) {
  switch (result) {
#define SDB_CASE(r) \
  case r:           \
    return #r;
    SDB_CASE(VK_SUCCESS)
    SDB_CASE(VK_NOT_READY)
    SDB_CASE(VK_TIMEOUT)
    SDB_CASE(VK_EVENT_SET)
    SDB_CASE(VK_EVENT_RESET)
    SDB_CASE(VK_INCOMPLETE)
    SDB_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    SDB_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    SDB_CASE(VK_ERROR_INITIALIZATION_FAILED)
    SDB_CASE(VK_ERROR_DEVICE_LOST)
    SDB_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    SDB_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    SDB_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    SDB_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    SDB_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    SDB_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    SDB_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    SDB_CASE(VK_ERROR_FRAGMENTED_POOL)
    SDB_CASE(VK_ERROR_UNKNOWN)
    SDB_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    SDB_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE)
    SDB_CASE(VK_ERROR_FRAGMENTATION)
    SDB_CASE(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
    SDB_CASE(VK_PIPELINE_COMPILE_REQUIRED)
    SDB_CASE(VK_ERROR_SURFACE_LOST_KHR)
    SDB_CASE(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
    SDB_CASE(VK_SUBOPTIMAL_KHR)
    SDB_CASE(VK_ERROR_OUT_OF_DATE_KHR)
    SDB_CASE(VK_ERROR_INCOMPATIBLE_DISPLAY_KHR)
    SDB_CASE(VK_ERROR_VALIDATION_FAILED_EXT)
    SDB_CASE(VK_ERROR_INVALID_SHADER_NV)
#undef SDB_CASE
    default:
      return "VkResult(" + std::to_string(static_cast<int>(result)) + ")";
  }
}

}  // namespace sdb::gpu
