#include "schemes/fragments/cpu.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <utility>

namespace sdb::fragments {

CpuFragmentEvaluation::CpuFragmentEvaluation(const ControlMesh& mesh, SubdivisionRule rule, int depth,
                                             bool multithreaded, int threads, bool project_to_limit)
    : control_(mesh.positions),
      // The refined points are level `depth`'s own; the limit is projected from a level deep
      // enough that no semi-sharp crease is left (surface.h).
      surface_(mesh, rule, depth, project_to_limit ? inner_depth_for(mesh, depth) : depth),
      multithreaded_(multithreaded),
      project_(project_to_limit) {
  if (multithreaded_ && threads > 0) arena_ = std::make_unique<tbb::task_arena>(threads);
  for (ShapeTables& t : surface_.tables) address_in_bytes(t);
  const Bounds box = bounds_of(control_);
  for (int k = 0; k < 3; ++k) origin_[k] = static_cast<float>(box.centre(k));
  surface_.describe(out_);
  out_.positions.resize(surface_.num_output_vertices);
  out_.normals.resize(surface_.num_output_vertices);
}

void CpuFragmentEvaluation::run_lanes(const FragmentSurface::Batch& batch, LaneBuffers& s) {
  if (s.a.size() < surface_.max_slots) {
    s.a.resize(surface_.max_slots), s.b.resize(surface_.max_slots), s.net.resize(surface_.max_slots);
    s.position.resize(surface_.max_limit_entries), s.normal.resize(surface_.max_limit_entries);
  }
  const std::vector<Fragment>& fragments = surface_.partition.fragments;
  const uint32_t* ids = surface_.order.data() + batch.begin;
  const ShapeTables& t = surface_.tables[fragments[ids[0]].shape];
  Lanes<kLanes>*src = s.a.data(), *dst = s.b.data();
  for (int l = 0; l < kLanes; ++l) {  // lanes past the batch repeat its last fragment
    const std::vector<int>& control = fragments[ids[std::min<uint32_t>(l, batch.count - 1)]].control;
    const Point3& first = control_[control[0]];
    for (size_t i = 0; i < control.size(); ++i) {
      const Point3& p = control_[control[i]];
      src[i].x[l] = p[0] - origin_[0], src[i].y[l] = p[1] - origin_[1], src[i].z[l] = p[2] - origin_[2];
      if (t.limit.net_size)
        s.net[i].x[l] = p[0] - first[0], s.net[i].y[l] = p[1] - first[1], s.net[i].z[l] = p[2] - first[2];
    }
  }
  const bool catmark = surface_.rule == SubdivisionRule::CatmullClark;
  for (const LevelTable& level : t.levels) {
    refine_level(level, catmark, src, dst);
    std::swap(src, dst);
  }
  project_to_limit(t.limit, src, s.net.data(), project_, s.position.data(), s.normal.data());
  float *pos[kLanes], *nrm[kLanes];
  for (uint32_t l = 0; l < kLanes; ++l) {
    const size_t first = surface_.first_vertex[ids[std::min<uint32_t>(l, batch.count - 1)]];
    pos[l] = out_.positions[first].data(), nrm[l] = out_.normals[first].data();
  }
  write_blocks(s.position.data(), s.normal.data(), static_cast<uint32_t>(t.block_vertices()), origin_, pos, nrm);
}

// A fragment of a shape of its own: its net refined twice at once, relative to the centre and
// relative to its first control point (kernel.h, Pair).
void CpuFragmentEvaluation::run_pair(uint32_t fragment, PairBuffers& s) {
  if (s.a.size() < surface_.max_slots) {
    s.level0.resize(surface_.max_slots), s.a.resize(surface_.max_slots), s.b.resize(surface_.max_slots);
    s.net.resize(surface_.max_slots);
    s.position.resize(surface_.max_limit_entries), s.normal.resize(surface_.max_limit_entries);
  }
  const Fragment& f = surface_.partition.fragments[fragment];
  const ShapeTables& t = surface_.tables[f.shape];
  const Point3& first = control_[f.control[0]];
  for (size_t i = 0; i < f.control.size(); ++i) {
    const Point3& p = control_[f.control[i]];
    const float x = p[0] - first[0], y = p[1] - first[1], z = p[2] - first[2];
    s.level0[i].pair = {{p[0] - origin_[0], p[1] - origin_[1], p[2] - origin_[2], 0}, {x, y, z, 0}};
    s.net[i] = {{x}, {y}, {z}};
  }
  const bool catmark = surface_.rule == SubdivisionRule::CatmullClark;
  const PairSlot* src = s.level0.data();
  PairSlot *dst = s.a.data(), *spare = s.b.data();
  for (const LevelTable& level : t.levels) {
    refine_level(level, catmark, src, dst);
    src = dst;
    std::swap(dst, spare);
  }
  project_to_limit(t.limit, src, s.level0.data(), s.net.data(), project_, s.position.data(), s.normal.data());
  Point3* pos = out_.positions.data() + surface_.first_vertex[fragment];
  Point3* nrm = out_.normals.data() + surface_.first_vertex[fragment];
  for (size_t i = 0; i < t.block_vertices(); ++i) {
    const Pair& p = s.position[i];
    const Lanes<1>& n = s.normal[i];
    pos[i] = {p.centred[0] + origin_[0], p.centred[1] + origin_[1], p.centred[2] + origin_[2]};
    nrm[i] = {n.x[0], n.y[0], n.z[0]};
  }
}

// A batch of one or two fragments runs them one at a time: eight lanes would be mostly idle.
void CpuFragmentEvaluation::run(const FragmentSurface::Batch& b, Scratch& s) {
  if (b.count > 2) return run_lanes(b, s.wide);
  for (uint32_t i = 0; i < b.count; ++i) run_pair(surface_.order[b.begin + i], s.narrow);
}

void CpuFragmentEvaluation::execute() {
  const std::vector<FragmentSurface::Batch>& batches = surface_.batches;
  if (!multithreaded_) {
    Scratch& s = scratch_.local();
    for (const FragmentSurface::Batch& b : batches) run(b, s);
    return;
  }
  auto go = [&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, batches.size(), 8), [&](const tbb::blocked_range<size_t>& r) {
      Scratch& s = scratch_.local();
      for (size_t i = r.begin(); i < r.end(); ++i) run(batches[i], s);
    });
  };
  if (arena_) arena_->execute(go);
  else go();
}

}  // namespace sdb::fragments
