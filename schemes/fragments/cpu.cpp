#include "schemes/fragments/cpu.h"

#include <tbb/parallel_for.h>

#include <utility>

namespace sdb::fragments {

CpuFragmentEvaluation::CpuFragmentEvaluation(const ControlMesh& mesh, SubdivisionRule rule, int depth,
                                             bool multithreaded, int threads, bool project_to_limit)
    : control_(mesh.positions), surface_(mesh, rule, depth), multithreaded_(multithreaded), project_(project_to_limit) {
  if (multithreaded_ && threads > 0) arena_ = std::make_unique<tbb::task_arena>(threads);
  const Bounds box = bounds_of(control_);
  origin_ = {static_cast<float>(box.centre(0)), static_cast<float>(box.centre(1)), static_cast<float>(box.centre(2))};
  surface_.describe(out_);
  out_.positions.resize(surface_.num_output_vertices);
  out_.normals.resize(surface_.num_output_vertices);
}

void CpuFragmentEvaluation::run_fragment(size_t f, Scratch& s) {
  if (s.a.size() < surface_.max_slots) {
    s.a.resize(surface_.max_slots), s.b.resize(surface_.max_slots);
    s.position.resize(surface_.max_limit_entries), s.normal.resize(surface_.max_limit_entries);
  }
  const Fragment& frag = surface_.partition.fragments[f];
  const ShapeTables& t = surface_.tables[frag.shape];
  Vec3 *src = s.a.data(), *dst = s.b.data();
  for (size_t i = 0; i < frag.control.size(); ++i) {
    const Point3& p = control_[frag.control[i]];
    src[i] = {p[0] - origin_.x, p[1] - origin_.y, p[2] - origin_.z};
  }
  const bool catmark = surface_.rule == SubdivisionRule::CatmullClark;
  for (const LevelTable& level : t.levels) {
    refine_level(level, catmark, src, dst);
    std::swap(src, dst);
  }
  if (project_) project_to_limit(t.limit, src, s.position.data(), s.normal.data());
  else refined_points(t.limit, src, s.position.data(), s.normal.data());
  Point3* pos = out_.positions.data() + surface_.first_vertex[f];
  Point3* nrm = out_.normals.data() + surface_.first_vertex[f];
  for (size_t i = 0; i < t.block.size(); ++i) {
    const Vec3 p = s.position[t.block[i]], n = s.normal[t.block_normal[i]];
    pos[i] = {p.x + origin_.x, p.y + origin_.y, p.z + origin_.z};
    nrm[i] = {n.x, n.y, n.z};
  }
}

void CpuFragmentEvaluation::execute() {
  const size_t count = surface_.partition.fragments.size();
  if (!multithreaded_) {
    Scratch& s = scratch_.local();
    for (size_t f = 0; f < count; ++f) run_fragment(f, s);
    return;
  }
  auto run = [&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 64), [&](const tbb::blocked_range<size_t>& r) {
      Scratch& s = scratch_.local();
      for (size_t f = r.begin(); f < r.end(); ++f) run_fragment(f, s);
    });
  };
  if (arena_) arena_->execute(run);
  else run();
}

}  // namespace sdb::fragments
