#include "harness/gpu/render_target.h"

#include <stdexcept>
#include <string>

#include "harness/gpu/errors.h"
#include "harness/gpu/memory.h"

namespace sdb::gpu {

RenderTarget::RenderTarget(Context& ctx, uint32_t width, uint32_t height)
    : ctx_(&ctx), width_(width), height_(height) {
  const DeviceLimits& l = ctx.limits();
  if (width == 0 || height == 0 || width > l.max_framebuffer_width || height > l.max_framebuffer_height)
    throw Unsupported("render target " + std::to_string(width) + "x" + std::to_string(height) + " outside what " +
                      ctx.info().name + " renders (up to " + std::to_string(l.max_framebuffer_width) + "x" +
                      std::to_string(l.max_framebuffer_height) + ")");
  try {
    colour_ = make_attachment(Context::k_colour_format,
                              VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                              VK_IMAGE_ASPECT_COLOR_BIT);
    depth_ = make_attachment(ctx.depth_format(), VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
    const VkImageView views[] = {colour_.view, depth_.view};
    VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    info.renderPass = ctx.offscreen_render_pass();
    info.attachmentCount = 2;
    info.pAttachments = views;
    info.width = width;
    info.height = height;
    info.layers = 1;
    check(ctx.vk().vkCreateFramebuffer(ctx.device(), &info, nullptr, &framebuffer_), "vkCreateFramebuffer",
          "creating the offscreen framebuffer");
  } catch (...) {
    destroy(colour_);
    destroy(depth_);
    throw;
  }
}

RenderTarget::~RenderTarget() {
  if (framebuffer_) ctx_->vk().vkDestroyFramebuffer(ctx_->device(), framebuffer_, nullptr);
  destroy(colour_);
  destroy(depth_);
}

RenderTarget::Attachment RenderTarget::make_attachment(VkFormat format, VkImageUsageFlags usage,
                                                       VkImageAspectFlags aspect) {
  const Vk& vk = ctx_->vk();
  VkDevice device = ctx_->device();
  Attachment a;
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {width_, height_, 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  const std::string doing = "creating a " + std::to_string(width_) + "x" + std::to_string(height_) + " render target";
  try {
    check(vk.vkCreateImage(device, &info, nullptr, &a.image), "vkCreateImage", doing);
    VkMemoryRequirements reqs;
    vk.vkGetImageMemoryRequirements(device, a.image, &reqs);
    const int type = choose_memory_type(ctx_->memory_properties(), reqs.memoryTypeBits, MemoryKind::Device);
    if (type < 0) throw Unsupported(ctx_->info().name + " has no memory type for " + doing);
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = reqs.size;
    alloc.memoryTypeIndex = static_cast<uint32_t>(type);
    check(vk.vkAllocateMemory(device, &alloc, nullptr, &a.memory), "vkAllocateMemory", doing);
    check(vk.vkBindImageMemory(device, a.image, a.memory, 0), "vkBindImageMemory", doing);
    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = a.image;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = format;
    view.subresourceRange = {aspect, 0, 1, 0, 1};
    check(vk.vkCreateImageView(device, &view, nullptr, &a.view), "vkCreateImageView", doing);
  } catch (...) {
    destroy(a);
    throw;
  }
  return a;
}

void RenderTarget::destroy(Attachment& a) {
  const Vk& vk = ctx_->vk();
  if (a.view) vk.vkDestroyImageView(ctx_->device(), a.view, nullptr);
  if (a.image) vk.vkDestroyImage(ctx_->device(), a.image, nullptr);
  if (a.memory) vk.vkFreeMemory(ctx_->device(), a.memory, nullptr);
  a = Attachment{};
}

void RenderTarget::begin(Commands& cmd, ClearColour clear) {
  VkClearValue clears[2]{};
  for (int i = 0; i < 4; ++i) clears[0].color.float32[i] = clear[i];
  clears[1].depthStencil = {1.0f, 0};
  VkRenderPassBeginInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  info.renderPass = ctx_->offscreen_render_pass();
  info.framebuffer = framebuffer_;
  info.renderArea = {{0, 0}, {width_, height_}};
  info.clearValueCount = 2;
  info.pClearValues = clears;
  const Vk& vk = ctx_->vk();
  cmd.begin_render_pass(info);
  const VkViewport viewport{0.0f, 0.0f, float(width_), float(height_), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, {width_, height_}};
  vk.vkCmdSetViewport(cmd.raw(), 0, 1, &viewport);
  vk.vkCmdSetScissor(cmd.raw(), 0, 1, &scissor);
  rendered_ = true;
}

void RenderTarget::end(Commands& cmd) { cmd.end_render_pass(); }

void RenderTarget::render(Commands& cmd, const std::function<void(Commands&)>& draw, ClearColour clear) {
  begin(cmd, clear);
  draw(cmd);
  end(cmd);
}

void RenderTarget::download(Commands& cmd, const Buffer& pixels) const {
  if (!rendered_) throw std::logic_error("RenderTarget::download before anything was rendered");
  if (pixels.size() < pixel_bytes())
    throw std::invalid_argument("RenderTarget::download: buffer '" + pixels.name() + "' holds " +
                                std::to_string(pixels.size()) + " bytes, the image " + std::to_string(pixel_bytes()));
  // The render pass's outgoing dependency already orders colour writes before transfer reads.
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {width_, height_, 1};
  ctx_->vk().vkCmdCopyImageToBuffer(cmd.raw(), colour_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, pixels.handle(), 1,
                                    &region);
  cmd.barrier(Stage::Transfer, Stage::Host);
}

Image RenderTarget::to_image(const Buffer& pixels) const {
  Image image;
  image.width = width_;
  image.height = height_;
  image.rgba.resize(pixel_bytes());
  pixels.read(image.rgba.data(), pixel_bytes());
  return image;
}

Image RenderTarget::read(Context& ctx) const {
  Buffer pixels = Buffer::readback(ctx, pixel_bytes(), "render target pixels");
  ctx.run([&](Commands& cmd) { download(cmd, pixels); });
  return to_image(pixels);
}

}  // namespace sdb::gpu
