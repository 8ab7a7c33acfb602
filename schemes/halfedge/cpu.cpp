// cpu and cpu-mt: each level's passes (halfedge/rules.h) as loops over the new points, on this
// thread or on TBB's; then the limit projection of the last level (harness/refined/limit.h).
#include "harness/refined/cpu_frame.h"
#include "schemes/halfedge/surface.h"

namespace sdb::halfedge {
namespace {

class CpuEvaluation final : public refined::CpuFrame {
 public:
  CpuEvaluation(const ControlMesh& mesh, SubdivisionRule rule, int depth, bool multithreaded, int threads, bool project)
      : CpuFrame(multithreaded, threads), control_(mesh.positions), s_(mesh, rule, depth, project) {
    points_.resize(s_.hierarchy.levels.size());
    for (size_t d = 0; d < points_.size(); ++d) points_[d].resize(s_.hierarchy.levels[d].num_vertices);
  }

  const Tessellation& output() const override { return s_.out; }

 private:
  void run() override {
    std::vector<Point3>& level0 = points_[0];
    const std::vector<uint32_t>& base = s_.hierarchy.base_vertices;
    for (size_t v = 0; v < level0.size(); ++v)
      for (int k = 0; k < 3; ++k) level0[v][k] = control_[base.empty() ? v : base[v]][k] - s_.origin[k];
    const auto& levels = s_.hierarchy.levels;
    for (int d = 0; d < s_.depth; ++d) {
      const Step step{&levels[d], &levels[d + 1], &s_.weights, bool(s_.hierarchy.creased[d]), points_[d].data(),
                      points_[d + 1].data()};
      refine_points(step, s_.rule, multithreaded_);
    }
    const std::vector<Point3>& last = points_.back();
    Tessellation& out = s_.out;
    if (s_.project) {
      refined::Projection p{last[0].data(), 3,
                            {s_.origin[0], s_.origin[1], s_.origin[2]}, out.positions.data(), out.normals.data(),
                            s_.early >= 0 ? points_[s_.early][0].data() : nullptr};
      refined::project(s_.limit, p, multithreaded_);
      return;
    }
    for (size_t v = 0; v < last.size(); ++v)  // the refined points themselves (the tests' oracle compares them)
      for (int k = 0; k < 3; ++k) out.positions[v][k] = last[v][k] + s_.origin[k];
  }

  std::vector<Point3> control_;
  Surface s_;
  std::vector<std::vector<Point3>> points_;
};

}  // namespace

std::unique_ptr<Evaluation> make_cpu_evaluation(const ControlMesh& mesh, SubdivisionRule rule, int depth,
                                                bool multithreaded, int threads, bool project_to_limit) {
  return std::make_unique<CpuEvaluation>(mesh, rule, depth, multithreaded, threads, project_to_limit);
}

}  // namespace sdb::halfedge
