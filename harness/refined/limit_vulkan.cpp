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
  return 4 * (uint64_t(p.regular_ring.size()) + p.special.size() + p.begin.size() + p.ring.size() + p.weights.size()) + 80;
}

VulkanLimit::VulkanLimit(gpu::Context& ctx, const LimitPlan& plan)
    : ctx_(&ctx),
      ring_size_(plan.ring_size),
      face_size_(plan.face_size),
      vertices_(plan.num_vertices),
      specials_(static_cast<uint32_t>(plan.special.size())),
      regular_ring_(gpu::texel_table(ctx, plan.regular_ring, "limit: regular rings")),
      special_(gpu::texel_table(ctx, plan.special, "limit: special vertices")),
      begin_(gpu::texel_table(ctx, plan.begin, "limit: entry ranges")),
      ring_(gpu::texel_table(ctx, plan.ring, "limit: ring vertices")),
      weights_(gpu::texel_table(ctx, plan.weights, "limit: mask weights")),
      regular_(gpu::shared_compute_pipeline(ctx, desc("limit_regular.comp"))),
      special_pass_(gpu::shared_compute_pipeline(ctx, desc("limit_special.comp"))) {}

void VulkanLimit::bind(const gpu::Buffer& points, const gpu::Buffer& positions, const gpu::Buffer& normals) {
  constexpr VkFormat u = VK_FORMAT_R32_UINT, f = VK_FORMAT_R32_SFLOAT;
  set_ = gpu::DescriptorSet(*regular_, {points.texels(VK_FORMAT_R32G32B32A32_SFLOAT), regular_ring_.texels(u),
                                        special_.texels(u), begin_.texels(u), ring_.texels(u), weights_.texels(f),
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
  if (specials_ == 0) return;
  // The two passes write disjoint vertices (a special one is skipped by the regular pass).
  timer.begin(cmd, gpu::PassKind::Kernel, "limit: special");
  cmd.bind(*special_pass_, set_);
  p.count = specials_;
  cmd.push(p);
  cmd.dispatch(gpu::groups_for(specials_, kLocalSize, ctx_->limits()));
  timer.end(cmd);
}

}  // namespace sdb::refined
