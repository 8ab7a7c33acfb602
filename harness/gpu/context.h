// Context: the Vulkan instance, the chosen device, its graphics+compute queue, a command pool, a
// pipeline cache and the offscreen render pass. Create one per process (shared_context()) and
// keep it alive longer than every object made from it. Record and submit from one thread at a
// time: the command pool is shared (submission itself is serialized).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "harness/gpu/device_info.h"
#include "harness/gpu/vk_functions.h"

namespace sdb::gpu {

class Commands;
class Pipeline;
class Recording;
struct PhysicalDevice;

enum class Validation {
  Default,  // on in debug builds (NDEBUG undefined) or with SUBDIVBENCH_VK_VALIDATION=1; off with =0
  On,       // on when VK_LAYER_KHRONOS_validation is installed
  Off,
};

struct ContextOptions {
  std::string device;  // case-insensitive name substring; empty: $SUBDIVBENCH_VK_DEVICE, then by type
  Validation validation = Validation::Default;
  bool sync_validation = false;  // the layer's synchronization checks as well (slower)
  bool print_validation = true;  // validation errors and warnings to stderr as they come
};

// What the validation layer said; errors are what tests assert on.
struct ValidationLog {
  std::atomic<uint64_t> errors{0};
  std::atomic<uint64_t> warnings{0};
  mutable std::mutex mutex;
  std::vector<std::string> messages;  // errors, the first k_kept of them
  bool print = true;
  static constexpr size_t k_kept = 64;
};

class Context {
 public:
  // Throws Unavailable (no loader, no usable device), VulkanError.
  static std::unique_ptr<Context> create(const ContextOptions& options = {});
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  const DeviceInfo& info() const { return info_; }
  const DeviceLimits& limits() const { return info_.limits; }
  const DeviceFeatures& features() const { return info_.features; }
  const Vk& vk() const { return vk_; }

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physical_device() const { return physical_device_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queue_family() const { return queue_family_; }
  VkPipelineCache pipeline_cache() const { return pipeline_cache_; }
  const VkPhysicalDeviceMemoryProperties& memory_properties() const { return memory_properties_; }

  // Every offscreen target shares this render pass (RGBA8 colour, cleared, kept for readback;
  // depth cleared); graphics pipelines are made against it.
  VkRenderPass offscreen_render_pass() const { return render_pass_; }
  static constexpr VkFormat k_colour_format = VK_FORMAT_R8G8B8A8_UNORM;
  VkFormat depth_format() const { return depth_format_; }

  bool validation_enabled() const { return validation_; }
  uint64_t validation_errors() const { return log_.errors.load(); }
  uint64_t validation_warnings() const { return log_.warnings.load(); }
  std::vector<std::string> validation_messages() const;

  // Pipelines shared by every user of this context, by key (pipeline.h: shared_compute_pipeline
  // makes the key and the pipeline); they live as long as the context.
  std::shared_ptr<const Pipeline> shared_pipeline(const std::string& key,
                                                  const std::function<std::shared_ptr<const Pipeline>()>& make);

  // Records commands into a fresh command buffer, submits it and waits for it to finish.
  void run(const std::function<void(Commands&)>& record);
  // Records once for many submissions (a scheme's execute()).
  Recording record(const std::function<void(Commands&)>& record);
  // Submits and waits; throws VulkanError (VK_TIMEOUT after 10 minutes, device lost, ...).
  void submit(const Recording& recording);
  void wait_idle() const;

 private:
  friend class Recording;
  Context() = default;
  void create_device(const PhysicalDevice& chosen);
  void create_render_pass();
  void create_debug_messenger();
  VkCommandBuffer allocate_command_buffer();
  void free_command_buffer(VkCommandBuffer cmd);
  void submit_and_wait(VkCommandBuffer cmd);

  Vk vk_;
  DeviceInfo info_;
  ValidationLog log_;
  bool validation_ = false;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
  VkPhysicalDeviceMemoryProperties memory_properties_{};
  VkDevice device_ = VK_NULL_HANDLE;
  uint32_t queue_family_ = 0;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkCommandPool command_pool_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkPipelineCache pipeline_cache_ = VK_NULL_HANDLE;
  VkRenderPass render_pass_ = VK_NULL_HANDLE;
  VkFormat depth_format_ = VK_FORMAT_UNDEFINED;
  std::mutex queue_mutex_;  // guards the queue, the command pool and the fence
  std::mutex pipelines_mutex_;
  std::map<std::string, std::shared_ptr<const Pipeline>> shared_pipelines_;  // destroyed before the device
};

// The process's Context, created on first call with `options` (later calls return the same one
// and ignore theirs). Throws Unavailable when there is no device; the next call tries again.
// It is not destroyed at exit (static destructors run after the driver's); call
// release_shared_context() before main returns for a clean teardown, once every user let go.
std::shared_ptr<Context> shared_context(const ContextOptions& options = {});
void release_shared_context();

}  // namespace sdb::gpu
