#include "harness/gpu/commands.h"

#include <stdexcept>
#include <string>
#include <utility>

namespace sdb::gpu {

namespace {

struct StageAccess {
  VkPipelineStageFlags stages;
  VkAccessFlags writes;  // what `from` makes available
  VkAccessFlags reads;   // what `to` is made visible for (its reads and writes)
};

StageAccess stage_access(Stage stage, const DeviceFeatures& features) {
  constexpr VkAccessFlags shader_rw = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_UNIFORM_READ_BIT;
  switch (stage) {
    case Stage::Host:
      return {VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_WRITE_BIT, VK_ACCESS_HOST_READ_BIT | VK_ACCESS_HOST_WRITE_BIT};
    case Stage::Transfer:
      return {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
              VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT};
    case Stage::Compute:
      return {VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, shader_rw};
    case Stage::Vertex: {
      // Stages of features the device lacks may not appear in a barrier.
      VkPipelineStageFlags stages =
          VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_VERTEX_INPUT_BIT | VK_PIPELINE_STAGE_VERTEX_SHADER_BIT;
      if (features.tessellation_shader)
        stages |= VK_PIPELINE_STAGE_TESSELLATION_CONTROL_SHADER_BIT | VK_PIPELINE_STAGE_TESSELLATION_EVALUATION_SHADER_BIT;
      if (features.geometry_shader) stages |= VK_PIPELINE_STAGE_GEOMETRY_SHADER_BIT;
      return {stages, VK_ACCESS_SHADER_WRITE_BIT,
              shader_rw | VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_INDEX_READ_BIT |
                  VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT};
    }
    case Stage::Fragment:
      return {VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, shader_rw};
    case Stage::All:
      return {VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
              VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT};
  }
  return {VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT, VK_ACCESS_MEMORY_READ_BIT};
}

uint64_t checked_span(const Buffer& buffer, uint64_t offset, uint64_t bytes, const char* what) {
  if (offset > buffer.size()) throw std::out_of_range(std::string(what) + ": offset past the end of '" + buffer.name() + "'");
  const uint64_t span = bytes == VK_WHOLE_SIZE ? buffer.size() - offset : bytes;
  if (span > buffer.size() - offset)
    throw std::out_of_range(std::string(what) + ": " + std::to_string(span) + " bytes at " + std::to_string(offset) +
                            " past the end of '" + buffer.name() + "' (" + std::to_string(buffer.size()) + " bytes)");
  return span;
}

}  // namespace

const Pipeline& Commands::bound(const char* what) const {
  if (!pipeline_) throw std::logic_error(std::string(what) + " before any pipeline was bound");
  return *pipeline_;
}

void Commands::bind(const Pipeline& pipeline) {
  ctx_->vk().vkCmdBindPipeline(cmd_, pipeline.bind_point(), pipeline.handle());
  pipeline_ = &pipeline;
}

void Commands::bind(const Pipeline& pipeline, const DescriptorSet& set) {
  bind(pipeline);
  bind(set);
}

void Commands::bind(const DescriptorSet& set) {
  const Pipeline& p = bound("binding a descriptor set");
  VkDescriptorSet handle = set.handle();
  if (!handle) return;  // a pipeline without bindings
  ctx_->vk().vkCmdBindDescriptorSets(cmd_, p.bind_point(), p.layout(), 0, 1, &handle, 0, nullptr);
}

void Commands::push_constants(const void* data, uint32_t bytes, uint32_t offset) {
  const Pipeline& p = bound("pushing constants");
  if (offset + bytes > p.push_constant_bytes())
    throw std::invalid_argument("pushing " + std::to_string(bytes) + " bytes of constants at " + std::to_string(offset) +
                                " into a pipeline declared with " + std::to_string(p.push_constant_bytes()));
  ctx_->vk().vkCmdPushConstants(cmd_, p.layout(), p.stages(), offset, bytes, data);
}

void Commands::dispatch(uint32_t x, uint32_t y, uint32_t z) {
  const auto& max = ctx_->limits().max_compute_work_group_count;
  if (x > max[0] || y > max[1] || z > max[2])
    throw std::invalid_argument("dispatch of " + std::to_string(x) + " x " + std::to_string(y) + " x " +
                                std::to_string(z) + " groups exceeds the device's maxComputeWorkGroupCount; use groups_for()");
  if (x == 0 || y == 0 || z == 0) return;
  ctx_->vk().vkCmdDispatch(cmd_, x, y, z);
  ++work_;
}

void Commands::barrier(Stage from, Stage to) {
  if (inside_render_pass_) throw std::logic_error("barrier inside a render pass");
  const StageAccess src = stage_access(from, ctx_->features());
  const StageAccess dst = stage_access(to, ctx_->features());
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = src.writes;
  barrier.dstAccessMask = dst.reads;
  ctx_->vk().vkCmdPipelineBarrier(cmd_, src.stages, dst.stages, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

void Commands::execution_barrier() {
  ctx_->vk().vkCmdPipelineBarrier(cmd_, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0,
                                  nullptr, 0, nullptr, 0, nullptr);
}

void Commands::begin_render_pass(const VkRenderPassBeginInfo& info) {
  if (inside_render_pass_) throw std::logic_error("render pass begun inside another");
  ctx_->vk().vkCmdBeginRenderPass(cmd_, &info, VK_SUBPASS_CONTENTS_INLINE);
  ++work_;
  inside_render_pass_ = true;
}

void Commands::end_render_pass() {
  if (!inside_render_pass_) throw std::logic_error("end of a render pass that was not begun");
  ctx_->vk().vkCmdEndRenderPass(cmd_);
  inside_render_pass_ = false;
}

void Commands::copy(const Buffer& src, const Buffer& dst, uint64_t bytes, uint64_t src_offset, uint64_t dst_offset) {
  const uint64_t span = checked_span(src, src_offset, bytes, "copy source");
  checked_span(dst, dst_offset, span, "copy destination");
  if (span == 0) return;
  VkBufferCopy region{src_offset, dst_offset, span};
  ctx_->vk().vkCmdCopyBuffer(cmd_, src.handle(), dst.handle(), 1, &region);
  ++work_;
}

void Commands::fill(const Buffer& dst, uint32_t value, uint64_t bytes, uint64_t offset) {
  const uint64_t span = checked_span(dst, offset, bytes, "fill");
  if (offset % 4 != 0 || (bytes != VK_WHOLE_SIZE && bytes % 4 != 0))
    throw std::invalid_argument("fill of '" + dst.name() + "': offset and size must be multiples of 4");
  if (span == 0) return;
  ctx_->vk().vkCmdFillBuffer(cmd_, dst.handle(), offset, bytes, value);
  ++work_;
}

void Commands::upload(const Buffer& staging, const Buffer& dst, uint64_t bytes, uint64_t src_offset,
                      uint64_t dst_offset) {
  copy(staging, dst, bytes, src_offset, dst_offset);
  barrier(Stage::Transfer, Stage::All);
}

void Commands::download(const Buffer& src, const Buffer& staging, uint64_t bytes, uint64_t src_offset,
                        uint64_t dst_offset) {
  barrier(Stage::All, Stage::Transfer);
  copy(src, staging, bytes, src_offset, dst_offset);
  barrier(Stage::Transfer, Stage::Host);
}

void Commands::bind_vertex_buffer(uint32_t binding, const Buffer& buffer, uint64_t offset) {
  VkBuffer handle = buffer.handle();
  ctx_->vk().vkCmdBindVertexBuffers(cmd_, binding, 1, &handle, &offset);
}

void Commands::bind_index_buffer(const Buffer& buffer, uint64_t offset) {
  ctx_->vk().vkCmdBindIndexBuffer(cmd_, buffer.handle(), offset, VK_INDEX_TYPE_UINT32);
}

void Commands::draw(uint32_t vertices, uint32_t instances, uint32_t first_vertex, uint32_t first_instance) {
  bound("draw");
  ctx_->vk().vkCmdDraw(cmd_, vertices, instances, first_vertex, first_instance);
  ++work_;
}

void Commands::draw_indexed(uint32_t indices, uint32_t instances, uint32_t first_index, int32_t vertex_offset,
                            uint32_t first_instance) {
  bound("draw_indexed");
  ctx_->vk().vkCmdDrawIndexed(cmd_, indices, instances, first_index, vertex_offset, first_instance);
  ++work_;
}

Recording::Recording(Recording&& other) noexcept { *this = std::move(other); }

Recording& Recording::operator=(Recording&& other) noexcept {
  if (this != &other) {
    release();
    ctx_ = std::exchange(other.ctx_, nullptr);
    cmd_ = std::exchange(other.cmd_, VK_NULL_HANDLE);
  }
  return *this;
}

Recording::~Recording() { release(); }

void Recording::release() {
  if (ctx_ && cmd_) ctx_->free_command_buffer(cmd_);
  ctx_ = nullptr;
  cmd_ = VK_NULL_HANDLE;
}

}  // namespace sdb::gpu
