// cpu and cpu-mt: the first step's stencils, then each level's kernel (rules.h) as one loop over
// its invocations, on this thread or on TBB's; then the limit projection of the last level
// (harness/refined/limit.h).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include "harness/refined/cpu_frame.h"
#include "schemes/edgefriend/surface.h"

namespace sdb::edgefriend {
namespace {

class CpuEvaluation final : public refined::CpuFrame {
 public:
  CpuEvaluation(const ControlMesh& mesh, int depth, bool multithreaded, int threads, bool project)
      : CpuFrame(multithreaded, threads), control_(mesh.positions), s_(mesh, depth, project) {
    const auto& levels = s_.hierarchy.levels;
    points_.resize(levels.size());
    for (size_t d = 0; d + 1 < levels.size(); ++d) points_[d].resize(levels[d].num_vertices);
    points_.back().resize(s_.hierarchy.out_vertices);  // in the output's numbering
  }

  const Tessellation& output() const override { return s_.out; }

 private:
  void first_step() {
    for (size_t v = 0; v < control_.size(); ++v)
      for (int k = 0; k < 3; ++k) relative_[v][k] = control_[v][k] - s_.origin[k];
    const uint32_t* out = s_.depth == 1 ? s_.out_index() : nullptr;
    const StencilTable& t = s_.stencils;
    if (!multithreaded_) return apply_stencils(t, relative_.data(), points_[0].data(), out, 0, t.rows());
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, t.rows(), 1024), [&](const tbb::blocked_range<uint32_t>& r) {
      apply_stencils(t, relative_.data(), points_[0].data(), out, r.begin(), r.end());
    });
  }

  void run() override {
    relative_.resize(control_.size());
    first_step();
    const auto& levels = s_.hierarchy.levels;
    for (int d = 1; d < s_.depth; ++d) {
      const Step step{&levels[d - 1], &s_.weights, points_[d - 1].data(), points_[d].data(),
                      d + 1 == s_.depth ? s_.out_index() : nullptr};
      refine_level_points(step, multithreaded_);
    }
    const std::vector<Point3>& last = points_.back();
    Tessellation& out = s_.out;
    if (s_.project) {
      refined::Projection p{last[0].data(), 3, {s_.origin[0], s_.origin[1], s_.origin[2]}, out.positions.data(),
                            out.normals.data(), s_.early >= 0 ? points_[s_.early][0].data() : nullptr};
      refined::project(s_.limit, p, multithreaded_);
      return;
    }
    for (size_t v = 0; v < last.size(); ++v)  // the refined points themselves (the tests' oracle compares them)
      for (int k = 0; k < 3; ++k) out.positions[v][k] = last[v][k] + s_.origin[k];
  }

  std::vector<Point3> control_, relative_;
  Surface s_;
  std::vector<std::vector<Point3>> points_;  // levels 1 .. depth
};

}  // namespace

std::unique_ptr<Evaluation> make_cpu_evaluation(const ControlMesh& mesh, int depth, bool multithreaded, int threads,
                                                bool project_to_limit) {
  return std::make_unique<CpuEvaluation>(mesh, depth, multithreaded, threads, project_to_limit);
}

}  // namespace sdb::edgefriend
