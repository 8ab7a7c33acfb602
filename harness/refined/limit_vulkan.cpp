#include "harness/refined/limit_vulkan.h"

#include "sdb_refined_shaders.h"

namespace sdb::refined {
namespace {

namespace shaders = sdb_refined_shaders;
constexpr uint32_t kLocalSize = 64;

struct Push {
  uint32_t count = 0, ring_size = 0, pad0 = 0, pad1 = 0;
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

}  // namespace

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
      regular_ring_(gpu::texel_table(ctx, plan.regular_ring, "limit: regular rings")),
      special_(ctx, plan.special, ""),
      early_(ctx, plan.early, " (early level)"),
      regular_(gpu::shared_compute_pipeline(ctx, desc("limit_regular.comp"))),
      special_pass_(gpu::shared_compute_pipeline(ctx, desc("limit_special.comp"))) {}

void VulkanLimit::bind(const gpu::Buffer& points, const gpu::Buffer& early_points, const gpu::Buffer& positions,
                       const gpu::Buffer& normals) {
  constexpr VkFormat u = VK_FORMAT_R32_UINT, f = VK_FORMAT_R32_SFLOAT, rgba = VK_FORMAT_R32G32B32A32_SFLOAT;
  set_ = gpu::DescriptorSet(*regular_, {points.texels(rgba), regular_ring_.texels(u), special_.vertex.texels(u),
                                        special_.begin.texels(u), special_.ring.texels(u), special_.weights.texels(f),
                                        positions.texels(f), normals.texels(f)});
  early_set_ = gpu::DescriptorSet(*special_pass_, {early_points.texels(rgba), regular_ring_.texels(u), early_.vertex.texels(u),
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
  cmd.bind(*regular_, set_);
  p.count = vertices_;
  cmd.push(p);
  cmd.dispatch(gpu::groups_for(vertices_, kLocalSize, ctx_->limits()));
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
