#include "harness/gpu/context.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "harness/gpu/commands.h"
#include "harness/gpu/errors.h"
#include "harness/gpu/loader.h"
#include "harness/gpu/physical_device.h"

namespace sdb::gpu {

namespace {

constexpr uint64_t k_submit_timeout_ns = uint64_t(600) * 1000 * 1000 * 1000;

bool validation_wanted(Validation v) {
  if (v != Validation::Default) return v == Validation::On;
  if (const char* env = std::getenv("SUBDIVBENCH_VK_VALIDATION")) return std::strcmp(env, "0") != 0;
#ifdef NDEBUG
  return false;
#else
  return true;
#endif
}

VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                     VkDebugUtilsMessageTypeFlagsEXT,
                                                     const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  auto* log = static_cast<ValidationLog*>(user);
  const char* text = data && data->pMessage ? data->pMessage : "(no message)";
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
    log->errors.fetch_add(1);
    std::lock_guard lock(log->mutex);
    if (log->messages.size() < ValidationLog::k_kept) log->messages.emplace_back(text);
    if (log->print) std::fprintf(stderr, "vulkan validation error: %s\n", text);
  } else if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
    log->warnings.fetch_add(1);
    if (log->print) std::fprintf(stderr, "vulkan validation warning: %s\n", text);
  }
  return VK_FALSE;  // never abort the call that triggered the message
}

// The features we enable when the device has them; a pipeline that needs a missing one is
// refused with a reason before creation (see pipeline.h).
VkPhysicalDeviceFeatures wanted_core_features(const VkPhysicalDeviceFeatures& has) {
  VkPhysicalDeviceFeatures f{};
  f.geometryShader = has.geometryShader;
  f.tessellationShader = has.tessellationShader;
  f.fillModeNonSolid = has.fillModeNonSolid;
  f.shaderFloat64 = has.shaderFloat64;
  f.shaderInt64 = has.shaderInt64;
  f.shaderInt16 = has.shaderInt16;
  f.vertexPipelineStoresAndAtomics = has.vertexPipelineStoresAndAtomics;
  f.fragmentStoresAndAtomics = has.fragmentStoresAndAtomics;
  f.multiDrawIndirect = has.multiDrawIndirect;
  f.drawIndirectFirstInstance = has.drawIndirectFirstInstance;
  return f;
}

VkFormat choose_depth_format(const Vk& vk, VkPhysicalDevice pd) {
  // The spec guarantees D16 and one of the 24/32-bit formats as depth attachments.
  for (VkFormat f : {VK_FORMAT_D32_SFLOAT, VK_FORMAT_X8_D24_UNORM_PACK32, VK_FORMAT_D16_UNORM}) {
    VkFormatProperties props;
    vk.vkGetPhysicalDeviceFormatProperties(pd, f, &props);
    if (props.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) return f;
  }
  return VK_FORMAT_D16_UNORM;
}

}  // namespace

std::unique_ptr<Context> Context::create(const ContextOptions& options) {
  const LoaderStatus& loader = vulkan_loader();
  if (!loader.get_instance_proc_addr) throw Unavailable(loader.reason);
  std::unique_ptr<Context> ctx(new Context());
  if (!load_global_functions(ctx->vk_, loader.get_instance_proc_addr))
    throw Unavailable("no Vulkan loader (libvulkan.so.1 lacks vkCreateInstance)");
  ctx->log_.print = options.print_validation;

  InstanceRequest request;
  request.validation = validation_wanted(options.validation);
  request.sync_validation = options.sync_validation;
  request.debug_utils = request.validation;
  InstanceResult instance = create_instance(ctx->vk_, request);
  ctx->instance_ = instance.instance;
  ctx->validation_ = instance.validation && instance.debug_utils;
  if (ctx->validation_) ctx->create_debug_messenger();

  std::vector<PhysicalDevice> devices = list_physical_devices(ctx->vk_, instance);
  std::vector<DeviceInfo> infos;
  for (const PhysicalDevice& d : devices) infos.push_back(d.info);
  DeviceChoice choice = choose_device(infos, options.device);
  if (choice.index < 0) throw Unavailable(choice.reason);
  ctx->create_device(devices[choice.index]);
  ctx->create_render_pass();
  return ctx;
}

void Context::create_debug_messenger() {
  VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT;
  // Performance hints (an output a later stage ignores, say) are advice, not errors; left out.
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
  info.pfnUserCallback = on_validation_message;
  info.pUserData = &log_;
  check(vk_.vkCreateDebugUtilsMessengerEXT(instance_, &info, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT",
        "installing the validation message callback");
}

void Context::create_device(const PhysicalDevice& chosen) {
  physical_device_ = chosen.handle;
  info_ = chosen.info;
  queue_family_ = chosen.queue_family;
  vk_.vkGetPhysicalDeviceMemoryProperties(physical_device_, &memory_properties_);

  const bool v12 = chosen.api_version >= VK_API_VERSION_1_2;
  VkPhysicalDeviceVulkan11Features has11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  VkPhysicalDeviceVulkan12Features has12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &has11};
  VkPhysicalDeviceFeatures2 has{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, v12 ? &has12 : nullptr};
  vk_.vkGetPhysicalDeviceFeatures2(physical_device_, &has);

  VkPhysicalDeviceVulkan11Features want11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  want11.storageBuffer16BitAccess = has11.storageBuffer16BitAccess;
  VkPhysicalDeviceVulkan12Features want12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &want11};
  want12.scalarBlockLayout = has12.scalarBlockLayout;
  want12.shaderFloat16 = has12.shaderFloat16;
  want12.shaderInt8 = has12.shaderInt8;
  want12.storageBuffer8BitAccess = has12.storageBuffer8BitAccess;
  VkPhysicalDeviceFeatures2 want{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, v12 ? &want12 : nullptr};
  want.features = wanted_core_features(has.features);

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue_info.queueFamilyIndex = queue_family_;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;
  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &want};
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue_info;
  check(vk_.vkCreateDevice(physical_device_, &info, nullptr, &device_), "vkCreateDevice",
        "creating the device on " + info_.name);
  load_device_functions(vk_, device_);
  vk_.vkGetDeviceQueue(device_, queue_family_, 0, &queue_);

  VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pool_info.queueFamilyIndex = queue_family_;
  check(vk_.vkCreateCommandPool(device_, &pool_info, nullptr, &command_pool_), "vkCreateCommandPool",
        "creating the command pool");
  VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  check(vk_.vkCreateFence(device_, &fence_info, nullptr, &fence_), "vkCreateFence", "creating the submission fence");
  VkPipelineCacheCreateInfo cache_info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
  check(vk_.vkCreatePipelineCache(device_, &cache_info, nullptr, &pipeline_cache_), "vkCreatePipelineCache",
        "creating the pipeline cache");
  depth_format_ = choose_depth_format(vk_, physical_device_);
}

void Context::create_render_pass() {
  VkAttachmentDescription attachments[2]{};
  attachments[0].format = k_colour_format;
  attachments[0].samples = VK_SAMPLE_COUNT_1_BIT;
  attachments[0].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  attachments[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  attachments[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  attachments[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  attachments[0].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;  // every frame starts cleared
  attachments[0].finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;  // ready to read back
  attachments[1] = attachments[0];
  attachments[1].format = depth_format_;
  attachments[1].storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  attachments[1].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;

  VkAttachmentReference colour_ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkAttachmentReference depth_ref{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &colour_ref;
  subpass.pDepthStencilAttachment = &depth_ref;

  // Before: the previous frame's readback of the colour image and its depth writes.
  // After: this frame's colour is read by a transfer.
  VkSubpassDependency deps[2]{};
  deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  deps[0].dstSubpass = 0;
  deps[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT;
  deps[0].srcAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  deps[1].srcSubpass = 0;
  deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  deps[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  deps[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;

  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = 2;
  info.pAttachments = attachments;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 2;
  info.pDependencies = deps;
  check(vk_.vkCreateRenderPass(device_, &info, nullptr, &render_pass_), "vkCreateRenderPass",
        "creating the offscreen render pass");
}

std::shared_ptr<const Pipeline> Context::shared_pipeline(const std::string& key,
                                                         const std::function<std::shared_ptr<const Pipeline>()>& make) {
  std::lock_guard<std::mutex> lock(pipelines_mutex_);
  auto it = shared_pipelines_.find(key);
  if (it == shared_pipelines_.end()) it = shared_pipelines_.emplace(key, make()).first;
  return it->second;
}

Context::~Context() {
  if (device_) {
    vk_.vkDeviceWaitIdle(device_);
    shared_pipelines_.clear();
    if (render_pass_) vk_.vkDestroyRenderPass(device_, render_pass_, nullptr);
    if (pipeline_cache_) vk_.vkDestroyPipelineCache(device_, pipeline_cache_, nullptr);
    if (fence_) vk_.vkDestroyFence(device_, fence_, nullptr);
    if (command_pool_) vk_.vkDestroyCommandPool(device_, command_pool_, nullptr);
    vk_.vkDestroyDevice(device_, nullptr);
  }
  if (messenger_) vk_.vkDestroyDebugUtilsMessengerEXT(instance_, messenger_, nullptr);
  if (instance_) vk_.vkDestroyInstance(instance_, nullptr);
}

std::vector<std::string> Context::validation_messages() const {
  std::lock_guard lock(log_.mutex);
  return log_.messages;
}

VkCommandBuffer Context::allocate_command_buffer() {
  VkCommandBufferAllocateInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  info.commandPool = command_pool_;
  info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  info.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  std::lock_guard lock(queue_mutex_);
  check(vk_.vkAllocateCommandBuffers(device_, &info, &cmd), "vkAllocateCommandBuffers", "allocating a command buffer");
  return cmd;
}

void Context::free_command_buffer(VkCommandBuffer cmd) {
  std::lock_guard lock(queue_mutex_);
  vk_.vkFreeCommandBuffers(device_, command_pool_, 1, &cmd);
}

void Context::submit_and_wait(VkCommandBuffer cmd) {
  std::lock_guard lock(queue_mutex_);
  VkSubmitInfo info{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  info.commandBufferCount = 1;
  info.pCommandBuffers = &cmd;
  check(vk_.vkQueueSubmit(queue_, 1, &info, fence_), "vkQueueSubmit", "submitting commands");
  const VkResult waited = vk_.vkWaitForFences(device_, 1, &fence_, VK_TRUE, k_submit_timeout_ns);
  // A timeout is an error: the work is still pending, so the context is unusable afterwards.
  if (waited == VK_TIMEOUT) throw VulkanError(VK_TIMEOUT, "vkWaitForFences", "waiting 600 s for submitted commands");
  check(waited, "vkWaitForFences", "waiting for submitted commands");
  check(vk_.vkResetFences(device_, 1, &fence_), "vkResetFences", "resetting the submission fence");
}

Recording Context::record(const std::function<void(Commands&)>& fn) {
  Recording recording(*this, allocate_command_buffer());
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  check(vk_.vkBeginCommandBuffer(recording.raw(), &begin), "vkBeginCommandBuffer", "recording commands");
  Commands commands(*this, recording.raw());
  fn(commands);
  check(vk_.vkEndCommandBuffer(recording.raw()), "vkEndCommandBuffer", "recording commands");
  return recording;
}

void Context::submit(const Recording& recording) { submit_and_wait(recording.raw()); }

void Context::run(const std::function<void(Commands&)>& fn) { submit(record(fn)); }

void Context::wait_idle() const { check(vk_.vkDeviceWaitIdle(device_), "vkDeviceWaitIdle", "waiting for the device"); }

namespace {
std::mutex shared_mutex;
// Heap-held and never destroyed at exit on purpose: static destructors run after the driver's own
// (LLVM's, for lavapipe), so tearing the device down there can crash. release_shared_context()
// tears it down while that is still safe.
std::shared_ptr<Context>* shared = new std::shared_ptr<Context>();
}  // namespace

std::shared_ptr<Context> shared_context(const ContextOptions& options) {
  std::lock_guard lock(shared_mutex);
  if (!*shared) *shared = Context::create(options);
  return *shared;
}

void release_shared_context() {
  std::lock_guard lock(shared_mutex);
  shared->reset();
}

}  // namespace sdb::gpu
