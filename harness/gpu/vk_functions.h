// The Vulkan entry points this module uses, loaded at run time (the build defines
// VK_NO_PROTOTYPES, so nothing links libvulkan). Global ones come from the loader library,
// instance ones from vkGetInstanceProcAddr(instance), device ones from vkGetDeviceProcAddr(device),
// which returns the driver's own functions without the loader's trampoline.
#pragma once

#ifndef VK_NO_PROTOTYPES
#define VK_NO_PROTOTYPES
#endif
#include <vulkan/vulkan.h>

#define SDB_VK_GLOBAL_FUNCTIONS(X)        \
  X(vkCreateInstance)                     \
  X(vkEnumerateInstanceVersion)           \
  X(vkEnumerateInstanceLayerProperties)   \
  X(vkEnumerateInstanceExtensionProperties)

#define SDB_VK_INSTANCE_FUNCTIONS(X)             \
  X(vkDestroyInstance)                           \
  X(vkEnumeratePhysicalDevices)                  \
  X(vkGetPhysicalDeviceProperties)               \
  X(vkGetPhysicalDeviceProperties2)              \
  X(vkGetPhysicalDeviceFeatures)                 \
  X(vkGetPhysicalDeviceFeatures2)                \
  X(vkGetPhysicalDeviceQueueFamilyProperties)    \
  X(vkGetPhysicalDeviceMemoryProperties)         \
  X(vkGetPhysicalDeviceFormatProperties)         \
  X(vkEnumerateDeviceExtensionProperties)        \
  X(vkCreateDevice)                              \
  X(vkGetDeviceProcAddr)                         \
  X(vkCreateDebugUtilsMessengerEXT)              \
  X(vkDestroyDebugUtilsMessengerEXT)

#define SDB_VK_DEVICE_FUNCTIONS(X)      \
  X(vkDestroyDevice)                    \
  X(vkGetDeviceQueue)                   \
  X(vkDeviceWaitIdle)                   \
  X(vkQueueSubmit)                      \
  X(vkCreateCommandPool)                \
  X(vkDestroyCommandPool)               \
  X(vkAllocateCommandBuffers)           \
  X(vkFreeCommandBuffers)               \
  X(vkBeginCommandBuffer)               \
  X(vkEndCommandBuffer)                 \
  X(vkCreateFence)                      \
  X(vkDestroyFence)                     \
  X(vkWaitForFences)                    \
  X(vkResetFences)                      \
  X(vkCreateBuffer)                     \
  X(vkDestroyBuffer)                    \
  X(vkGetBufferMemoryRequirements)      \
  X(vkAllocateMemory)                   \
  X(vkFreeMemory)                       \
  X(vkBindBufferMemory)                 \
  X(vkMapMemory)                        \
  X(vkUnmapMemory)                      \
  X(vkFlushMappedMemoryRanges)          \
  X(vkInvalidateMappedMemoryRanges)     \
  X(vkCreateImage)                      \
  X(vkDestroyImage)                     \
  X(vkGetImageMemoryRequirements)       \
  X(vkBindImageMemory)                  \
  X(vkCreateImageView)                  \
  X(vkDestroyImageView)                 \
  X(vkCreateRenderPass)                 \
  X(vkDestroyRenderPass)                \
  X(vkCreateFramebuffer)                \
  X(vkDestroyFramebuffer)               \
  X(vkCreateShaderModule)               \
  X(vkDestroyShaderModule)              \
  X(vkCreatePipelineCache)              \
  X(vkDestroyPipelineCache)             \
  X(vkCreateDescriptorSetLayout)        \
  X(vkDestroyDescriptorSetLayout)       \
  X(vkCreatePipelineLayout)             \
  X(vkDestroyPipelineLayout)            \
  X(vkCreateComputePipelines)           \
  X(vkCreateGraphicsPipelines)          \
  X(vkDestroyPipeline)                  \
  X(vkCreateDescriptorPool)             \
  X(vkDestroyDescriptorPool)            \
  X(vkCreateBufferView)                 \
  X(vkDestroyBufferView)                \
  X(vkAllocateDescriptorSets)           \
  X(vkUpdateDescriptorSets)             \
  X(vkCreateQueryPool)                  \
  X(vkDestroyQueryPool)                 \
  X(vkGetQueryPoolResults)              \
  X(vkCmdResetQueryPool)                \
  X(vkCmdWriteTimestamp)                \
  X(vkCmdBindPipeline)                  \
  X(vkCmdBindDescriptorSets)            \
  X(vkCmdPushConstants)                 \
  X(vkCmdDispatch)                      \
  X(vkCmdDispatchIndirect)              \
  X(vkCmdPipelineBarrier)               \
  X(vkCmdCopyBuffer)                    \
  X(vkCmdFillBuffer)                    \
  X(vkCmdCopyImageToBuffer)             \
  X(vkCmdBeginRenderPass)               \
  X(vkCmdEndRenderPass)                 \
  X(vkCmdSetViewport)                   \
  X(vkCmdSetScissor)                    \
  X(vkCmdBindVertexBuffers)             \
  X(vkCmdBindIndexBuffer)               \
  X(vkCmdDraw)                          \
  X(vkCmdDrawIndexed)                   \
  X(vkCmdDrawIndirect)                  \
  X(vkCmdDrawIndexedIndirect)

namespace sdb::gpu {

// One table per instance/device pair. A member is null when the loader or driver lacks it
// (vkEnumerateInstanceVersion on a 1.0 loader; the debug-utils pair when that extension is off).
struct Vk {
  PFN_vkGetInstanceProcAddr vkGetInstanceProcAddr = nullptr;
#define SDB_VK_MEMBER(name) PFN_##name name = nullptr;
  SDB_VK_GLOBAL_FUNCTIONS(SDB_VK_MEMBER)
  SDB_VK_INSTANCE_FUNCTIONS(SDB_VK_MEMBER)
  SDB_VK_DEVICE_FUNCTIONS(SDB_VK_MEMBER)
#undef SDB_VK_MEMBER
};

}  // namespace sdb::gpu
