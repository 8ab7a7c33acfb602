#include "harness/refined/limit_vulkan.h"

#include <algorithm>
#include <vector>

#include "harness/refined/face_level.h"
#include "sdb_refined_shaders.h"

namespace sdb::refined {
namespace {

namespace shaders = sdb_refined_shaders;
constexpr uint32_t kLocalSize = 64;

struct Push {
  uint32_t count = 0, ring_size = 0, first = 0, pad = 0;
  float origin[4] = {0, 0, 0, 0};
  float k[4] = {0, 0, 0, 0};
};

gpu::ComputePipelineDesc desc(const char* shader) {
  using gpu::Binding;
  return {shaders::get(shader),
          {Binding::UniformTexelBuffer, Binding::UniformTexelBuffer, Binding::UniformTexelBuffer,
           Binding::UniformTexelBuffer, Binding::UniformTexelBuffer, Binding::UniformTexelBuffer,
           Binding::StorageTexelBuffer, Binding::StorageTexelBuffer},
          sizeof(Push),
          {{0, kLocalSize}}};
}

uint64_t ring_view_entries_for_testing = 0;

// The regular rings cut into views: a chunk is whole vertices' rings, at most one texel view (and one
// storage binding, one buffer: plan_chunks' other limits) long.
gpu::ChunkPlan plan_ring_chunks(const gpu::DeviceLimits& limits, const LimitPlan& plan) {
  const uint64_t vertices = std::max<uint64_t>(plan.regular_ring.size() / plan.ring_size, 1);
  uint64_t entries = limits.max_texel_buffer_elements;
  if (ring_view_entries_for_testing > 0) entries = std::min(entries, ring_view_entries_for_testing);
  return gpu::plan_chunks(limits, {vertices, 4 * plan.ring_size, 1, kLocalSize, 4 * entries});
}

// The chunks' buffers, each holding its chunks' rings at their offsets.
std::vector<gpu::Buffer> upload_rings(gpu::Context& ctx, const gpu::ChunkPlan& chunks, const LimitPlan& plan) {
  std::vector<uint32_t> rings = plan.regular_ring;
  rings.resize(std::max<size_t>(rings.size(), plan.ring_size), kNone);
  std::vector<gpu::Buffer> buffers;
  for (size_t b = 0; b < chunks.buffer_bytes.size(); ++b)
    buffers.push_back(gpu::Buffer::device(ctx, chunks.buffer_bytes[b], gpu::BufferUsage::UniformTexel,
                                          "limit: regular rings (" + std::to_string(b) + ")"));
  for (const gpu::Chunk& c : chunks.chunks)
    gpu::upload(ctx, buffers[c.buffer], rings.data() + c.first_element * plan.ring_size, c.bytes, c.byte_offset);
  return buffers;
}

}  // namespace

void limit_ring_view_entries_for_testing(uint64_t entries) { ring_view_entries_for_testing = entries; }

uint64_t VulkanLimit::table_bytes(const LimitPlan& p) {
  uint64_t words = p.regular_ring.size();
  for (const SpecialTable* t : {&p.special, &p.early}) words += t->vertex.size() + t->begin.size() + t->ring.size() + t->weights.size();
  return 4 * words + 160;
}

VulkanLimit::Table::Table(gpu::Context& ctx, const SpecialTable& t, const std::string& level)
    : count(t.size()),
      vertex(gpu::texel_table(ctx, t.vertex, "limit: special vertices" + level)),
      begin(gpu::texel_table(ctx, t.begin, "limit: entry ranges" + level)),
      ring(gpu::texel_table(ctx, t.ring, "limit: ring vertices" + level)),
      weights(gpu::texel_table(ctx, t.weights, "limit: mask weights" + level)) {}

VulkanLimit::VulkanLimit(gpu::Context& ctx, const LimitPlan& plan)
    : ctx_(&ctx),
      ring_size_(plan.ring_size),
      face_size_(plan.face_size),
      vertices_(plan.num_vertices),
      ring_chunks_(plan_ring_chunks(ctx.limits(), plan)),
      regular_ring_(upload_rings(ctx, ring_chunks_, plan)),
      special_(ctx, plan.special, ""),
      early_(ctx, plan.early, " (early level)"),
      regular_(gpu::shared_compute_pipeline(ctx, desc("limit_regular.comp"))),
      special_pass_(gpu::shared_compute_pipeline(ctx, desc("limit_special.comp"))) {}

void VulkanLimit::bind(const gpu::Buffer& points, const gpu::Buffer& early_points, const gpu::Buffer& positions,
                       const gpu::Buffer& normals) {
  constexpr VkFormat u = VK_FORMAT_R32_UINT, f = VK_FORMAT_R32_SFLOAT, rgba = VK_FORMAT_R32G32B32A32_SFLOAT;
  regular_sets_.clear();
  for (const gpu::Chunk& c : ring_chunks_.chunks)
    regular_sets_.emplace_back(*regular_, std::vector{points.texels(rgba), regular_ring_[c.buffer].texels(u, c.byte_offset, c.bytes),
                                                      special_.vertex.texels(u), special_.begin.texels(u), special_.ring.texels(u),
                                                      special_.weights.texels(f), positions.texels(f), normals.texels(f)});
  // The special pass reads no regular ring; binding 1 takes the first view.
  const gpu::Chunk& first = ring_chunks_.chunks.front();
  const gpu::BufferRange some_rings = regular_ring_[first.buffer].texels(u, first.byte_offset, first.bytes);
  set_ = gpu::DescriptorSet(*special_pass_, {points.texels(rgba), some_rings, special_.vertex.texels(u),
                                             special_.begin.texels(u), special_.ring.texels(u), special_.weights.texels(f),
                                             positions.texels(f), normals.texels(f)});
  early_set_ = gpu::DescriptorSet(*special_pass_, {early_points.texels(rgba), some_rings, early_.vertex.texels(u),
                                                   early_.begin.texels(u), early_.ring.texels(u), early_.weights.texels(f),
                                                   positions.texels(f), normals.texels(f)});
}

void VulkanLimit::record(gpu::Commands& cmd, gpu::GpuTimer& timer, const float origin[3]) const {
  Push p;
  p.ring_size = ring_size_;
  for (int k = 0; k < 3; ++k) p.origin[k] = origin[k];
  const RegularConstants rc = regular_constants(face_size_);
  for (int k = 0; k < 3; ++k) p.k[k] = rc.k[k];
  timer.begin(cmd, gpu::PassKind::Kernel, "limit: regular");
  for (size_t i = 0; i < ring_chunks_.chunks.size(); ++i) {
    const gpu::Chunk& c = ring_chunks_.chunks[i];
    if (c.first_element >= vertices_) break;  // a plan without vertices has one chunk of one kNone ring
    cmd.bind(*regular_, regular_sets_[i]);
    p.first = static_cast<uint32_t>(c.first_element);
    p.count = static_cast<uint32_t>(std::min<uint64_t>(c.elements, vertices_ - c.first_element));
    cmd.push(p);
    cmd.dispatch(c.groups);
  }
  p.first = 0;
  timer.end(cmd);
  if (special_.count + early_.count == 0) return;
  // The passes write disjoint vertices (a special one is skipped by the regular pass, and is in one
  // table).
  timer.begin(cmd, gpu::PassKind::Kernel, "limit: special");
  for (const auto& [table, set] : {std::pair{&special_, &set_}, std::pair{&early_, &early_set_}}) {
    if (table->count == 0) continue;
    cmd.bind(*special_pass_, *set);
    p.count = table->count;
    cmd.push(p);
    cmd.dispatch(gpu::groups_for(table->count, kLocalSize, ctx_->limits()));
  }
  timer.end(cmd);
}

}  // namespace sdb::refined
