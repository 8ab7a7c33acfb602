#include "schemes/halfedge/vulkan.h"

#include <array>
#include <cstdio>
#include <stdexcept>

#include "harness/gpu/gpu.h"
#include "harness/refined/requests.h"
#include "harness/refined/vulkan_frame.h"
#include "schemes/halfedge/surface.h"
#include "sdb_scheme_halfedge_shaders.h"

namespace sdb::halfedge {
namespace {

namespace shaders = sdb_scheme_halfedge_shaders;
using gpu::BufferUsage;
constexpr uint32_t kCreased = 1, kChildSharp = 2;  // halfedge.glsl

struct Push {
  uint32_t count = 0, vertices = 0, faces = 0, edges = 0, face_size = 0, flags = 0;
  uint32_t base_next = 0, base_prev = 0, base_face = 0, base_first = 0;
};

// A level's buffers on the device: its halfedges and, where it has any, its sharpness.
struct LevelBuffers {
  gpu::Buffer points, twin, vert, edge, edge_corner, vertex_corner, edge_sharpness, vertex_sharpness;
};

template <class T>
gpu::Buffer table(gpu::Context& c, const std::vector<T>& values, const std::string& name) {
  return gpu::texel_table(c, values, name);
}

class VulkanEvaluation final : public refined::VulkanFrame {
 public:
  VulkanEvaluation(const ControlMesh& mesh, SubdivisionRule rule, int depth, bool project, std::shared_ptr<gpu::Context> ctx)
      : VulkanEvaluation(std::make_unique<Surface>(mesh, rule, depth, project), mesh, std::move(ctx)) {}

 private:
  VulkanEvaluation(std::unique_ptr<Surface> s, const ControlMesh& mesh, std::shared_ptr<gpu::Context> ctx)
      : VulkanFrame(std::move(ctx), mesh.positions, s->hierarchy.base_vertices, s->origin, s->out), s_(std::move(s)) {
    if (uploaded() != levels()[0].num_vertices) throw std::logic_error("halfedge: level 0 is not the uploaded points");
    check_device();
    make_buffers();
    make_sets();
    record_frame(buffers_[0].points, uint32_t(passes_.size()) * s_->depth,
                 [&](gpu::Commands& cmd, gpu::GpuTimer& timer) {
                   for (int d = 0; d < s_->depth; ++d) record_level(cmd, timer, d);
                 });
  }

  const std::vector<Level>& levels() const { return s_->hierarchy.levels; }

  // Every buffer against the device's limits and heaps before one is made.
  void check_device() {
    uint64_t device = 0;
    const Level& last = s_->last();
    for (size_t d = 0; d < levels().size(); ++d) {
      const Level& l = levels()[d];
      device += 16 * uint64_t(l.num_vertices);
      if (&l != &last) {
        gpu::check_texel_binding(ctx(), l.num_halfedges, "a level's halfedges");
        device += 4 * (3 * l.num_halfedges + l.num_edges + l.num_vertices);
      }
      device += 4 * (l.edge_sharpness.size() + l.vertex_sharpness.size());
    }
    VulkanFrame::check_device(device, s_->project ? &s_->limit : nullptr, "depth " + std::to_string(s_->depth));
  }

  void make_buffers() {
    gpu::Context& c = ctx();
    make_output_buffers();
    const std::vector<float> none{0.0f};
    for (size_t d = 0; d < levels().size(); ++d) {
      const Level& l = levels()[d];
      const std::string at = " (level " + std::to_string(d) + ")";
      LevelBuffers b;
      b.points = gpu::Buffer::device(c, std::max<uint64_t>(16 * uint64_t(l.num_vertices), 16),
                                     BufferUsage::UniformTexel | BufferUsage::StorageTexel, "points" + at);
      if (d + 1 < levels().size()) {  // the last level's halfedges are not read (surface.h)
        b.twin = table(c, l.twin, "twins" + at);
        b.vert = table(c, l.vert, "vertices" + at);
        b.edge = table(c, l.edge, "edges" + at);
        b.edge_corner = table(c, l.edge_corner, "edge halfedges" + at);
        b.vertex_corner = table(c, l.vertex_corner, "vertex halfedges" + at);
      }
      b.edge_sharpness = table(c, l.edge_sharpness.empty() ? none : l.edge_sharpness, "edge sharpness" + at);
      b.vertex_sharpness = table(c, l.vertex_sharpness.empty() ? none : l.vertex_sharpness, "vertex sharpness" + at);
      buffers_.push_back(std::move(b));
    }
    const Level& l0 = levels()[0];
    std::vector<uint32_t> base{0};
    if (l0.face_size == 0) {
      base_next_ = 0, base_prev_ = uint32_t(l0.next_of.size()), base_face_ = 2 * base_prev_, base_first_ = 3 * base_prev_;
      base = l0.next_of;
      base.insert(base.end(), l0.prev_of.begin(), l0.prev_of.end());
      base.insert(base.end(), l0.face_of.begin(), l0.face_of.end());
      base.insert(base.end(), l0.face_first.begin(), l0.face_first.end());
    }
    base_ = table(c, base, "base level's next, prev, face");
    const SmoothWeights& w = s_->weights;
    std::vector<float> weights = w.vertex;
    weights.insert(weights.end(), w.ring.begin(), w.ring.end());
    weights.insert(weights.end(), w.inverse.begin(), w.inverse.end());
    weights_ = table(c, weights, "smooth masks");
  }

  gpu::ComputePipelineDesc desc(const char* shader) const {
    using gpu::Binding;
    std::vector<Binding> b(14, Binding::UniformTexelBuffer);
    b[1] = Binding::StorageTexelBuffer;
    return {shaders::get(shader), b, sizeof(Push), {{0, kLocalSize}}};
  }

  void make_sets() {
    const bool loop = s_->rule == SubdivisionRule::Loop;
    passes_ = loop ? std::vector<std::string>{"loop_edges.comp", "loop_vertices.comp"}
                   : std::vector<std::string>{"cc_faces.comp", "cc_edges.comp", "cc_vertices.comp"};
    for (const std::string& p : passes_) pipelines_.push_back(gpu::shared_compute_pipeline(ctx(), desc(p.c_str())));
    for (int d = 0; d < s_->depth; ++d) {
      const LevelBuffers &p = buffers_[d], &c = buffers_[d + 1];
      sets_.emplace_back(*pipelines_[0],
                         std::vector<gpu::BufferRange>{p.points.texels(kPoint), c.points.texels(kPoint), c.points.texels(kPoint),
                                                       p.twin.texels(kWord), p.vert.texels(kWord), p.edge.texels(kWord),
                                                       p.edge_corner.texels(kWord), p.vertex_corner.texels(kWord),
                                                       p.edge_sharpness.texels(kFloat), p.vertex_sharpness.texels(kFloat),
                                                       c.edge_sharpness.texels(kFloat), c.vertex_sharpness.texels(kFloat),
                                                       weights_.texels(kFloat), base_.texels(kWord)});
    }
    const LevelBuffers& last = buffers_.back();  // its points only
    bind_output(s_->project ? &s_->limit : nullptr, last.points,
                buffers_[s_->early >= 0 ? s_->early : buffers_.size() - 1].points);
  }

  // Level d's passes: their counts, names and the level's flags.
  void record_level(gpu::Commands& cmd, gpu::GpuTimer& timer, int d) {
    const Level &l = levels()[d], &c = levels()[d + 1];
    Push push;
    push.vertices = l.num_vertices, push.faces = l.num_faces, push.edges = l.num_edges, push.face_size = l.face_size;
    push.flags = (s_->hierarchy.creased[d] ? kCreased : 0) | (c.edge_sharpness.empty() ? 0 : kChildSharp);
    push.base_next = base_next_, push.base_prev = base_prev_, push.base_face = base_face_, push.base_first = base_first_;
    const bool loop = s_->rule == SubdivisionRule::Loop;
    const std::array<uint32_t, 3> counts = loop ? std::array<uint32_t, 3>{l.num_edges, l.num_vertices, 0}
                                                : std::array<uint32_t, 3>{l.num_faces, l.num_edges, l.num_vertices};
    const char* names[3] = {loop ? "edges" : "faces", loop ? "vertices" : "edges", "vertices"};
    for (size_t k = 0; k < passes_.size(); ++k) {
      timer.begin(cmd, gpu::PassKind::Kernel, "depth " + std::to_string(d + 1) + ": " + names[k]);
      cmd.bind(*pipelines_[k], sets_[d]);
      push.count = counts[k];
      cmd.push(push);
      if (counts[k] > 0) cmd.dispatch(gpu::groups_for(counts[k], kLocalSize, ctx().limits()));
      timer.end(cmd);
      cmd.barrier(gpu::Stage::Compute, gpu::Stage::Compute);
    }
  }

  std::unique_ptr<Surface> s_;
  gpu::Buffer base_, weights_;
  uint32_t base_next_ = 0, base_prev_ = 0, base_face_ = 0, base_first_ = 0;
  std::vector<LevelBuffers> buffers_;
  std::vector<std::string> passes_;
  std::vector<std::shared_ptr<const gpu::ComputePipeline>> pipelines_;
  std::vector<gpu::DescriptorSet> sets_;
};

}  // namespace

std::unique_ptr<Evaluation> make_vulkan_evaluation(const ControlMesh& mesh, SubdivisionRule rule, int depth,
                                                   bool project_to_limit) {
  if (auto why = refined::vulkan_unavailable()) throw gpu::Unsupported(*why);
  return std::make_unique<VulkanEvaluation>(mesh, rule, depth, project_to_limit, gpu::shared_context());
}

}  // namespace sdb::halfedge
