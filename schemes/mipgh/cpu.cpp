#include "schemes/mipgh/cpu.h"

#include <algorithm>
#include <utility>

#include "schemes/mipgh/primitives.h"

namespace sdb::mipgh {

CpuMipghEvaluation::CpuMipghEvaluation(const ControlMesh& mesh, MeshRule rule, DAtlas atlas, int depth,
                                       bool multithreaded, int threads, bool project_to_limit,
                                       AdaptiveCriterion criterion)
    : control_(mesh.positions),
      m_(mesh, rule, std::move(atlas), depth, project_to_limit, criterion),
      multithreaded_(multithreaded) {
  if (multithreaded_ && threads > 0) arena_ = std::make_unique<tbb::task_arena>(threads);
  const uint32_t inner_nodes = m_.lod.most_nodes(m_.inner_depth());
  uint32_t nodes = m_.lod.layout(depth).num_nodes;
  if (m_.lod.adaptive()) {
    adaptive_ = compile_adaptive(m_.atlas, m_.lod, m_.render, m_.home, out_);
    nodes = uint32_t(out_.coords.size());
    if (m_.project()) limit_.resize(inner_nodes);  // the normals of a level's projection
  } else {
    compile_primitives(m_.atlas, m_.lod, depth, out_);
  }
  a_.resize(inner_nodes), b_.resize(inner_nodes);
  if (!m_.base_tangents.empty()) base_.resize(control_.size());
  if (!m_.pick.empty()) limit_.resize(inner_nodes);
  // A triangle's (u, v) is Loop's parametrization, which names no point of the Catmull-Clark
  // reference (whose ptex faces split a triangle in three): quad/triangle rows carry none.
  if (rule == MeshRule::QuadTri) out_.coords.clear();
  out_.positions.resize(nodes);
  out_.normals.resize(nodes);
}

void CpuMipghEvaluation::run() {
  const float* o = m_.origin;
  for (size_t v = 0; v < control_.size(); ++v) a_[v] = {control_[v][0] - o[0], control_[v][1] - o[1], control_[v][2] - o[2]};
  // Level 0 as given, kept for the normals taken from it (vertex_tangents.h, regular_patches.h)
  if (!m_.base_tangents.empty())
    for (size_t v = 0; v < control_.size(); ++v) base_[v] = {control_[v][0], control_[v][1], control_[v][2]};
  V3 *src = a_.data(), *dst = b_.data();
  if (m_.lod.adaptive()) {
    for (int sigma = 0; sigma <= m_.inner_depth(); ++sigma) {
      if (sigma > 0) m_.processor.step(sigma - 1, src, dst, multithreaded_), std::swap(src, dst);
      output_level(sigma, src, dst);
    }
    return;
  }
  for (int sigma = 0; sigma < m_.inner_depth(); ++sigma) {
    // Before the projection, the regular D-facets' targets that it reads alone (processor.h)
    const bool last = m_.project() && sigma + 1 == m_.inner_depth();
    m_.processor.step(sigma, src, dst, multithreaded_, last ? &m_.patches : nullptr);
    std::swap(src, dst);
  }
  const size_t n = out_.positions.size();
  if (!m_.project()) {  // the last step's nodes; no normals (the paper's mutation steps alone)
    for (size_t i = 0; i < n; ++i) out_.positions[i] = {src[i].x + o[0], src[i].y + o[1], src[i].z + o[2]};
    return;
  }
  // The limit is written straight into the output, moved back by the origin there; or over the
  // spare buffer and limit_ where the depth's grid points are picked from a deeper level.
  const std::vector<uint32_t>& pick = m_.pick;
  const BaseLevel base{m_.base_tangents, base_.data(), &m_.patches, &m_.facet_masks, {o[0], o[1], o[2]}};
  if (pick.empty()) {
    const V3 origin{o[0], o[1], o[2]};
    m_.processor.project(m_.inner_depth(), src, reinterpret_cast<V3*>(out_.positions.data()),
                         reinterpret_cast<V3*>(out_.normals.data()), multithreaded_, &origin, &base);
    return;
  }
  m_.processor.project(m_.inner_depth(), src, dst, limit_.data(), multithreaded_, nullptr, &base);
  for (size_t i = 0; i < n; ++i) {
    const size_t k = pick[i];
    out_.positions[i] = {dst[k].x + o[0], dst[k].y + o[1], dst[k].z + o[2]};
    out_.normals[i] = {limit_[k].x, limit_[k].y, limit_[k].z};
  }
}

void CpuMipghEvaluation::output_level(int sigma, const V3* src, V3* spare) {
  const auto& nodes = adaptive_.nodes[sigma];
  if (nodes.empty()) return;
  const float* o = m_.origin;
  if (!m_.project()) {
    for (const auto& [at, i] : nodes) out_.positions[i] = {src[at].x + o[0], src[at].y + o[1], src[at].z + o[2]};
    return;
  }
  const BaseLevel base{m_.base_tangents, base_.data(), &m_.patches, &m_.facet_masks, {o[0], o[1], o[2]}};
  m_.processor.project(sigma, src, spare, limit_.data(), adaptive_.homes[sigma], multithreaded_, &base);
  for (const auto& [at, i] : nodes) {
    out_.positions[i] = {spare[at].x + o[0], spare[at].y + o[1], spare[at].z + o[2]};
    out_.normals[i] = {limit_[at].x, limit_[at].y, limit_[at].z};
  }
}

void CpuMipghEvaluation::execute() {
  if (arena_) arena_->execute([&] { run(); });
  else run();
}

}  // namespace sdb::mipgh
