// RenderTarget: an offscreen RGBA8 colour + depth target of any size, rendered with the
// context's offscreen render pass, and read back to the host.
//
//   target.begin(cmd, clear);  ...bind a GraphicsPipeline, draw...;  target.end(cmd);
//   target.download(cmd, pixels);   // or, blocking, after submission: Image image = target.read(ctx);
//
// A scheme records its own draw between begin() and end() (or through render()), with its own
// GraphicsPipeline; for frames per second, wrap begin..end in a GpuTimer pass of kind Draw.
#pragma once

#include <array>
#include <cstdint>
#include <functional>

#include "harness/gpu/buffer.h"
#include "harness/gpu/commands.h"
#include "harness/gpu/context.h"
#include "harness/gpu/image.h"

namespace sdb::gpu {

using ClearColour = std::array<float, 4>;  // RGBA in [0, 1]
inline constexpr ClearColour k_white{1.0f, 1.0f, 1.0f, 1.0f};

class RenderTarget {
 public:
  // Throws Unsupported beyond the device's framebuffer size, VulkanError.
  RenderTarget(Context& ctx, uint32_t width, uint32_t height);
  ~RenderTarget();
  RenderTarget(const RenderTarget&) = delete;
  RenderTarget& operator=(const RenderTarget&) = delete;

  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  float aspect() const { return float(width_) / float(height_); }
  VkRenderPass render_pass() const { return ctx_->offscreen_render_pass(); }
  VkFramebuffer framebuffer() const { return framebuffer_; }
  VkImage colour_image() const { return colour_.image; }

  // Starts the render pass (colour cleared to `clear`, depth to 1) and sets the viewport and
  // scissor to the whole target.
  void begin(Commands& cmd, ClearColour clear = k_white);
  void end(Commands& cmd);
  void render(Commands& cmd, const std::function<void(Commands&)>& draw, ClearColour clear = k_white);

  uint64_t pixel_bytes() const { return uint64_t(width_) * height_ * 4; }
  // After end(): copies the colour image into `pixels` (pixel_bytes() of Readback memory) and
  // makes it visible to the host.
  void download(Commands& cmd, const Buffer& pixels) const;
  Image to_image(const Buffer& pixels) const;
  // Blocking: the last frame rendered, through a temporary readback buffer.
  Image read(Context& ctx) const;

 private:
  struct Attachment {
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
  };
  Attachment make_attachment(VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect);
  void destroy(Attachment& a);

  Context* ctx_;
  uint32_t width_, height_;
  Attachment colour_, depth_;
  VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
  bool rendered_ = false;  // a render pass was recorded, so the colour image has a defined layout
};

}  // namespace sdb::gpu
