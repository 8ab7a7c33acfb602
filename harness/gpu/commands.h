// Commands: recording into one command buffer, with the few operations schemes need;
// raw() gives the VkCommandBuffer for anything else (with context().vk() for the functions).
// Recording: a recorded command buffer that can be submitted many times (Context::submit).
#pragma once

#include <array>
#include <cstdint>

#include "harness/gpu/buffer.h"
#include "harness/gpu/context.h"
#include "harness/gpu/pipeline.h"

namespace sdb::gpu {

// Pipeline stages for barriers, coarse on purpose: what wrote before, what reads after.
enum class Stage {
  Host,      // the CPU, through mapped memory
  Transfer,  // copies and fills
  Compute,   // compute shaders
  Vertex,    // vertex input (vertex, index, indirect buffers) and the vertex..geometry shader stages
  Fragment,  // fragment shaders
  All,       // everything
};

// Work-group counts of one dispatch.
struct Groups {
  uint32_t x = 1, y = 1, z = 1;
};

class Commands {
 public:
  Commands(Context& ctx, VkCommandBuffer cmd) : ctx_(&ctx), cmd_(cmd) {}

  VkCommandBuffer raw() const { return cmd_; }
  Context& context() const { return *ctx_; }
  // Work commands recorded so far (dispatch, copy, fill, draw, render pass): GpuTimer shares a
  // timestamp between two passes with none in between. Work through raw() is not counted.
  uint64_t work_recorded() const { return work_; }

  // Binds the pipeline, and its descriptor set (set 0) when given; later push() and dispatch()
  // or draw calls go to this pipeline.
  void bind(const Pipeline& pipeline);
  void bind(const Pipeline& pipeline, const DescriptorSet& set);
  void bind(const DescriptorSet& set);  // to the bound pipeline
  void push_constants(const void* data, uint32_t bytes, uint32_t offset = 0);
  template <class T>
  void push(const T& value) {
    push_constants(&value, sizeof(T));
  }

  void dispatch(uint32_t x, uint32_t y = 1, uint32_t z = 1);
  void dispatch(Groups groups) { dispatch(groups.x, groups.y, groups.z); }

  // A memory barrier: writes of `from` are visible to reads and writes of `to`.
  void barrier(Stage from, Stage to);
  // Every later command waits for every earlier one to finish; no memory visibility.
  void execution_barrier();

  void copy(const Buffer& src, const Buffer& dst, uint64_t bytes = VK_WHOLE_SIZE, uint64_t src_offset = 0,
            uint64_t dst_offset = 0);
  void fill(const Buffer& dst, uint32_t value, uint64_t bytes = VK_WHOLE_SIZE, uint64_t offset = 0);
  // Staging in: copy, then a barrier so that every later stage sees the data.
  void upload(const Buffer& staging, const Buffer& dst, uint64_t bytes = VK_WHOLE_SIZE, uint64_t src_offset = 0,
              uint64_t dst_offset = 0);
  // Staging out: a barrier after every earlier write, the copy, and a barrier to the host.
  void download(const Buffer& src, const Buffer& staging, uint64_t bytes = VK_WHOLE_SIZE, uint64_t src_offset = 0,
                uint64_t dst_offset = 0);

  // RenderTarget::begin/end call these; barriers are not allowed in between.
  void begin_render_pass(const VkRenderPassBeginInfo& info);
  void end_render_pass();
  bool inside_render_pass() const { return inside_render_pass_; }

  // Inside RenderTarget::begin/end.
  void bind_vertex_buffer(uint32_t binding, const Buffer& buffer, uint64_t offset = 0);
  void bind_index_buffer(const Buffer& buffer, uint64_t offset = 0);  // uint32 indices
  void draw(uint32_t vertices, uint32_t instances = 1, uint32_t first_vertex = 0, uint32_t first_instance = 0);
  void draw_indexed(uint32_t indices, uint32_t instances = 1, uint32_t first_index = 0, int32_t vertex_offset = 0,
                    uint32_t first_instance = 0);

 private:
  const Pipeline& bound(const char* what) const;

  Context* ctx_;
  VkCommandBuffer cmd_;
  const Pipeline* pipeline_ = nullptr;
  bool inside_render_pass_ = false;
  uint64_t work_ = 0;
};

class Recording {
 public:
  Recording(Context& ctx, VkCommandBuffer cmd) : ctx_(&ctx), cmd_(cmd) {}
  Recording(Recording&& other) noexcept;
  Recording& operator=(Recording&& other) noexcept;
  Recording(const Recording&) = delete;
  Recording& operator=(const Recording&) = delete;
  ~Recording();

  VkCommandBuffer raw() const { return cmd_; }

 private:
  void release();
  Context* ctx_ = nullptr;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
};

}  // namespace sdb::gpu
