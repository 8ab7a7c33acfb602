#include "schemes/mipgh/cpu.h"

#include <algorithm>
#include <utility>

#include "harness/core/errors.h"
#include "harness/mesh/osd_topology.h"

namespace sdb::mipgh {
namespace {

// Level sigma's depth for the limit: deeper where semi-sharp creases outlast the depth.
int inner_depth(const ControlMesh& mesh, int depth, bool project) { return project ? limit_depth_for(mesh, depth) : depth; }

}  // namespace

CpuMipghEvaluation::Topology CpuMipghEvaluation::topology_of(const ControlMesh& mesh, SubdivisionRule rule,
                                                             DAtlas atlas, int inner) {
  const auto refiner = make_refiner(mesh, rule);
  const auto& base = refiner->GetLevel(0);
  // Far makes holes of the faces it is told of, and under the boundary rule "none" of every face
  // at a boundary vertex: primitive compilation skips the same ones.
  for (int f = 0; f < atlas.num_facets(); ++f) atlas.facet_hole[f] |= base.IsFaceHole(f);
  EdgeTags tags = build_tags(atlas, base, sdc_options(mesh), inner);
  return {std::move(atlas), std::move(tags)};
}

CpuMipghEvaluation::CpuMipghEvaluation(const ControlMesh& mesh, SubdivisionRule rule, DAtlas atlas, int depth,
                                       bool multithreaded, int threads, bool project_to_limit)
    : CpuMipghEvaluation(mesh, rule,
                         topology_of(mesh, rule, std::move(atlas), inner_depth(mesh, depth, project_to_limit)), depth,
                         multithreaded, threads, project_to_limit) {}

CpuMipghEvaluation::CpuMipghEvaluation(const ControlMesh& mesh, SubdivisionRule rule, Topology topology, int depth,
                                       bool multithreaded, int threads, bool project_to_limit)
    : control_(mesh.positions),
      atlas_(std::move(topology.atlas)),
      lod_(atlas_, inner_depth(mesh, depth, project_to_limit)),
      tags_(std::move(topology.tags)),
      shader_(make_shader(rule, sdc_options(mesh))),
      processor_(atlas_, lod_, tags_, *shader_),
      multithreaded_(multithreaded),
      project_(project_to_limit) {
  if (multithreaded_ && threads > 0) arena_ = std::make_unique<tbb::task_arena>(threads);
  for (int v = 0; v < atlas_.num_vertices; ++v)
    if (atlas_.vertex_fans[v] > 1 && !(tags_.any && tags_.vertex[0][v] >= 10.0f))
      throw InputError(mesh.source, "vertex " + std::to_string(v) +
                                        " joins several fans of faces and is not an infinitely sharp corner");
  const Bounds box = bounds_of(control_);
  for (int k = 0; k < 3; ++k) origin_[k] = static_cast<float>(box.centre(k));
  const uint32_t inner_nodes = lod_.layout(lod_.depth()).num_nodes, nodes = lod_.layout(depth).num_nodes;
  a_.resize(inner_nodes), b_.resize(inner_nodes);
  if (lod_.depth() > depth) pick_ = same_points_at(atlas_, lod_, depth, lod_.depth()), limit_.resize(inner_nodes);
  compile_primitives(atlas_, lod_, depth, out_);
  out_.positions.resize(nodes);
  out_.normals.resize(nodes);
}

void CpuMipghEvaluation::run() {
  for (size_t v = 0; v < control_.size(); ++v)
    a_[v] = {control_[v][0] - origin_[0], control_[v][1] - origin_[1], control_[v][2] - origin_[2]};
  V3 *src = a_.data(), *dst = b_.data();
  for (int sigma = 0; sigma < lod_.depth(); ++sigma) {
    processor_.step(sigma, src, dst, multithreaded_);
    std::swap(src, dst);
  }
  const size_t n = out_.positions.size();
  if (!project_) {  // the last step's nodes; no normals (the paper's mutation steps alone)
    for (size_t i = 0; i < n; ++i) out_.positions[i] = {src[i].x + origin_[0], src[i].y + origin_[1], src[i].z + origin_[2]};
    return;
  }
  // The limit is written over the spare buffer and the normals straight into the output, or
  // through limit_ where the depth's grid points are picked from a deeper level.
  V3* normal = pick_.empty() ? reinterpret_cast<V3*>(out_.normals.data()) : limit_.data();
  processor_.project(lod_.depth(), src, dst, normal, multithreaded_);
  for (size_t i = 0; i < n; ++i) {
    const size_t k = pick_.empty() ? i : pick_[i];
    out_.positions[i] = {dst[k].x + origin_[0], dst[k].y + origin_[1], dst[k].z + origin_[2]};
    if (!pick_.empty()) out_.normals[i] = {limit_[k].x, limit_[k].y, limit_[k].z};
  }
}

void CpuMipghEvaluation::execute() {
  if (arena_) arena_->execute([&] { run(); });
  else run();
}

}  // namespace sdb::mipgh
