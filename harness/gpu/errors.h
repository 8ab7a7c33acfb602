// Errors of the Vulkan backend. Each what() is one line: what was being done and, for a failed
// Vulkan call, the VkResult name. The CLI maps them to exit codes and result statuses:
//   Unavailable  no loader or no usable device: the vulkan backend is skipped ("unavailable").
//   Unsupported  the device lacks a feature or limit a request needs: the run is "unsupported".
//   VulkanError  a Vulkan call failed (out of memory, device lost, ...): an internal error.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

#include "harness/core/errors.h"
#include "harness/gpu/vk_functions.h"

namespace sdb::gpu {

class Unavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The harness-wide Unsupported (harness/core/errors.h): a device limit is one of the limits a
// request runs into, and becomes an "unsupported" row like any other.
using Unsupported = sdb::Unsupported;

class VulkanError : public std::runtime_error {
 public:
  VulkanError(VkResult result, std::string_view call, std::string_view doing);
  VkResult result() const { return result_; }

 private:
  VkResult result_;
};

// "VK_ERROR_OUT_OF_DEVICE_MEMORY"; "VkResult(<n>)" for codes this build does not know.
std::string to_string(VkResult result);

// Throws VulkanError unless result is VK_SUCCESS (or another non-negative status: a warning such
// as VK_INCOMPLETE is not an error). `call` is the Vulkan function, `doing` says for what.
inline void check(VkResult result, std::string_view call, std::string_view doing) {
  if (result < 0) throw VulkanError(result, call, doing);
}

}  // namespace sdb::gpu
