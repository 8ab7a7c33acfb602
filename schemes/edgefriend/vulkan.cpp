#include "schemes/edgefriend/vulkan.h"

#include <array>
#include <cstdio>

#include "harness/gpu/gpu.h"
#include "harness/refined/requests.h"
#include "harness/refined/vulkan_frame.h"
#include "schemes/edgefriend/surface.h"
#include "sdb_scheme_edgefriend_shaders.h"

namespace sdb::edgefriend {
namespace {

namespace shaders = sdb_scheme_edgefriend_shaders;
using gpu::BufferUsage;
constexpr VkFormat kWord4 = VK_FORMAT_R32G32B32A32_UINT;
constexpr uint32_t kCreased = 1, kVertexSharp = 2, kOutIndex = 4;  // shaders/level.comp

struct LevelPush {
  uint32_t count = 0, vertices = 0, quads = 0, flags = 0;
};
struct StencilPush {
  uint32_t count = 0, flags = 0;
};

// A level's buffers on the device: its points and, but on the last level, its quads.
struct LevelBuffers {
  gpu::Buffer points, quads, friends, vertex_corner, vertex_sharpness;
};

class VulkanEvaluation final : public refined::VulkanFrame {
 public:
  VulkanEvaluation(const ControlMesh& mesh, int depth, bool project, std::shared_ptr<gpu::Context> ctx)
      : VulkanEvaluation(std::make_unique<Surface>(mesh, depth, project), mesh, std::move(ctx)) {}

 private:
  VulkanEvaluation(std::unique_ptr<Surface> s, const ControlMesh& mesh, std::shared_ptr<gpu::Context> ctx)
      : VulkanFrame(std::move(ctx), mesh.positions, {}, s->origin, s->out), s_(std::move(s)) {
    check_device();
    make_buffers();
    make_sets();
    record_frame(control_points_, uint32_t(s_->depth), [&](gpu::Commands& cmd, gpu::GpuTimer& timer) { record_levels(cmd, timer); });
  }

  const std::vector<Level>& levels() const { return s_->hierarchy.levels; }
  uint32_t points_of(size_t d) const { return d + 1 == levels().size() ? s_->hierarchy.out_vertices : levels()[d].num_vertices; }

  // Every buffer against the device's limits and heaps before one is made.
  void check_device() {
    uint64_t device = 16 * uint64_t(uploaded()) + 4 * (s_->stencils.begin.size() + 2 * s_->stencils.source.size());
    for (size_t d = 0; d < levels().size(); ++d) {
      const Level& l = levels()[d];
      gpu::check_texel_binding(ctx(), points_of(d), "a level's points");
      device += 16 * uint64_t(points_of(d));
      if (d + 1 < levels().size()) {
        gpu::check_texel_binding(ctx(), l.num_vertices, "a level's vertices");
        device += 32 * uint64_t(l.num_quads) + 4 * uint64_t(l.num_vertices) + 4 * l.vertex_sharpness.size();
      }
    }
    device += 4 * s_->hierarchy.out_index.size() + 12 * (kMaxValence + 1);
    VulkanFrame::check_device(device, s_->project ? &s_->limit : nullptr, "depth " + std::to_string(s_->depth));
  }

  void make_buffers() {
    gpu::Context& c = ctx();
    make_output_buffers();
    control_points_ = gpu::Buffer::device(c, std::max<uint64_t>(16 * uint64_t(uploaded()), 16), BufferUsage::UniformTexel,
                                          "control points");
    const StencilTable& t = s_->stencils;
    begin_ = gpu::texel_table(c, t.begin, "first step: stencil rows");
    source_ = gpu::texel_table(c, t.source, "first step: stencil sources");
    weight_ = gpu::texel_table(c, t.weight, "first step: stencil weights");
    out_index_ = gpu::texel_table(c, s_->hierarchy.out_index, "output numbering");
    for (size_t d = 0; d < levels().size(); ++d) {
      const Level& l = levels()[d];
      const std::string at = " (depth " + std::to_string(d + 1) + ")";
      LevelBuffers b;
      b.points = gpu::Buffer::device(c, std::max<uint64_t>(16 * uint64_t(points_of(d)), 16),
                                     BufferUsage::UniformTexel | BufferUsage::StorageTexel, "points" + at);
      if (d + 1 < levels().size()) {  // the last level's quads are not read (surface.h)
        std::vector<std::array<uint32_t, 4>> quads(l.num_quads);
        for (uint32_t q = 0; q < l.num_quads; ++q) std::copy_n(&l.indices[4 * uint64_t(q)], 4, quads[q].begin());
        b.quads = gpu::texel_table(c, quads, "quads" + at);
        b.friends = gpu::texel_table(c, l.friends, "friends" + at);
        b.vertex_corner = gpu::texel_table(c, l.vertex_corner, "vertex corners" + at);
        b.vertex_sharpness = gpu::texel_table(c, l.vertex_sharpness, "vertex sharpness" + at);
      }
      buffers_.push_back(std::move(b));
    }
    std::vector<float> weights = s_->weights.vertex;
    weights.insert(weights.end(), s_->weights.edge.begin(), s_->weights.edge.end());
    weights.insert(weights.end(), s_->weights.diagonal.begin(), s_->weights.diagonal.end());
    weights_ = gpu::texel_table(c, weights, "smooth masks");
  }

  void make_sets() {
    using gpu::Binding;
    constexpr auto U = Binding::UniformTexelBuffer, S = Binding::StorageTexelBuffer;
    first_ = gpu::shared_compute_pipeline(ctx(), {shaders::get("first_step.comp"), {U, S, U, U, U, U}, sizeof(StencilPush), {{0, kLocalSize}}});
    first_set_ = gpu::DescriptorSet(*first_, {control_points_.texels(kPoint), buffers_[0].points.texels(kPoint), begin_.texels(kWord),
                                              source_.texels(kWord), weight_.texels(kFloat), out_index_.texels(kWord)});
    level_ = gpu::shared_compute_pipeline(ctx(), {shaders::get("level.comp"), {U, S, U, U, U, U, U, U}, sizeof(LevelPush), {{0, kLocalSize}}});
    for (size_t d = 0; d + 1 < levels().size(); ++d) {
      const LevelBuffers &p = buffers_[d], &n = buffers_[d + 1];
      sets_.emplace_back(*level_, std::vector<gpu::BufferRange>{p.points.texels(kPoint), n.points.texels(kPoint), p.quads.texels(kWord4),
                                                                p.friends.texels(kWord4), p.vertex_corner.texels(kWord),
                                                                p.vertex_sharpness.texels(kFloat), weights_.texels(kFloat),
                                                                out_index_.texels(kWord)});
    }
    bind_output(s_->project ? &s_->limit : nullptr, buffers_.back().points,
                buffers_[s_->early >= 0 ? s_->early : buffers_.size() - 1].points);
  }

  // "depth 1: first step", then one "depth d: edge-friend" dispatch a level.
  void record_levels(gpu::Commands& cmd, gpu::GpuTimer& timer) {
    const bool out_index = !s_->hierarchy.out_index.empty();
    StencilPush sp;
    sp.count = s_->stencils.rows();
    sp.flags = s_->depth == 1 && out_index ? kOutIndex : 0;
    timer.begin(cmd, gpu::PassKind::Kernel, "depth 1: first step");
    cmd.bind(*first_, first_set_);
    cmd.push(sp);
    cmd.dispatch(gpu::groups_for(sp.count, kLocalSize, ctx().limits()));
    timer.end(cmd);
    cmd.barrier(gpu::Stage::Compute, gpu::Stage::Compute);
    for (int d = 1; d < s_->depth; ++d) {
      const Level& l = levels()[d - 1];
      LevelPush p;
      p.count = invocations(l), p.vertices = l.num_vertices, p.quads = l.num_quads;
      p.flags = (l.creased ? kCreased : 0) | (l.vertex_sharpness.empty() ? 0 : kVertexSharp) |
                (d + 1 == s_->depth && out_index ? kOutIndex : 0);
      timer.begin(cmd, gpu::PassKind::Kernel, "depth " + std::to_string(d + 1) + ": edge-friend");
      cmd.bind(*level_, sets_[d - 1]);
      cmd.push(p);
      cmd.dispatch(gpu::groups_for(p.count, kLocalSize, ctx().limits()));
      timer.end(cmd);
      cmd.barrier(gpu::Stage::Compute, gpu::Stage::Compute);
    }
  }

  std::unique_ptr<Surface> s_;
  gpu::Buffer control_points_, begin_, source_, weight_, out_index_, weights_;
  std::vector<LevelBuffers> buffers_;
  std::shared_ptr<const gpu::ComputePipeline> first_, level_;
  gpu::DescriptorSet first_set_;
  std::vector<gpu::DescriptorSet> sets_;
};

}  // namespace

std::unique_ptr<Evaluation> make_vulkan_evaluation(const ControlMesh& mesh, int depth, bool project_to_limit) {
  if (auto why = refined::vulkan_unavailable()) throw gpu::Unsupported(*why);
  return std::make_unique<VulkanEvaluation>(mesh, depth, project_to_limit, gpu::shared_context());
}

}  // namespace sdb::edgefriend
