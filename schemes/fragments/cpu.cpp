#include "schemes/fragments/cpu.h"

#include "schemes/fragments/block_writer.h"

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
  const Bounds box = bounds_of(control_);
  for (int k = 0; k < 3; ++k) origin_[k] = static_cast<float>(box.centre(k));
  surface_.describe(out_);
  out_.positions.resize(surface_.num_output_vertices);
  out_.normals.resize(surface_.num_output_vertices);
}

template <int W>
void CpuFragmentEvaluation::run_batch(const FragmentSurface::Batch& batch, Buffers<W>& s) {
  if (s.a.size() < surface_.max_slots) {
    s.a.resize(surface_.max_slots), s.b.resize(surface_.max_slots), s.net.resize(surface_.max_slots);
    s.position.resize(surface_.max_limit_entries), s.normal.resize(surface_.max_limit_entries);
  }
  const std::vector<Fragment>& fragments = surface_.partition.fragments;
  const uint32_t* ids = surface_.order.data() + batch.begin;
  const ShapeTables& t = surface_.tables[fragments[ids[0]].shape];
  Lanes<W>*src = s.a.data(), *dst = s.b.data();
  for (int l = 0; l < W; ++l) {  // lanes past the batch repeat its last fragment
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
  const int lanes = static_cast<int>(std::min<uint32_t>(batch.count, W));
  if constexpr (W == kLanes) {
    if (t.block_in_order) {
      Point3 *pos[kLanes], *nrm[kLanes];
      for (int l = 0; l < kLanes; ++l) {
        const size_t first = surface_.first_vertex[ids[std::min(l, lanes - 1)]];
        pos[l] = out_.positions.data() + first, nrm[l] = out_.normals.data() + first;
      }
      write_blocks_in_order(s.position.data(), s.normal.data(), t.block.size(), origin_, pos, nrm, lanes);
      return;
    }
  }
  for (int l = 0; l < lanes; ++l) {
    Point3* pos = out_.positions.data() + surface_.first_vertex[ids[l]];
    Point3* nrm = out_.normals.data() + surface_.first_vertex[ids[l]];
    for (size_t i = 0; i < t.block.size(); ++i) {
      const Lanes<W>&p = s.position[t.block[i]], &n = s.normal[t.block_normal[i]];
      pos[i] = {p.x[l] + origin_[0], p.y[l] + origin_[1], p.z[l] + origin_[2]};
      nrm[i] = {n.x[l], n.y[l], n.z[l]};
    }
  }
}

// A batch of one or two fragments runs them one at a time: eight lanes would be mostly idle.
void CpuFragmentEvaluation::run(const FragmentSurface::Batch& b, Scratch& s) {
  if (b.count > 2) return run_batch(b, s.wide);
  for (uint32_t i = 0; i < b.count; ++i) run_batch({b.begin + i, 1}, s.narrow);
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
