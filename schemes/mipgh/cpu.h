// cpu and cpu-mt: the mesh processor on the host, one node after another (cpu) or the D-facets,
// D-edges and D-vertices of each visit in parallel on TBB (cpu-mt).
#pragma once

#include <tbb/task_arena.h>

#include <memory>
#include <vector>

#include "harness/core/scheme.h"
#include "schemes/mipgh/mutation.h"
#include "schemes/mipgh/primitives.h"

namespace sdb::mipgh {

class CpuMipghEvaluation final : public Evaluation {
 public:
  // `atlas`: the mesh's (build_atlas), as the size check in prepare built it.
  CpuMipghEvaluation(const ControlMesh& mesh, MeshRule rule, DAtlas atlas, int depth, bool multithreaded,
                     int threads, bool project_to_limit, AdaptiveCriterion criterion = {});
  void execute() override;
  const Tessellation& result() override { return out_; }
  size_t bytes_out() const override { return out_.positions.size() * 2 * sizeof(Point3); }

 private:
  void run();
  // Adaptive: each level's output nodes, projected there or copied (compile_adaptive).
  void output_level(int sigma, const V3* src, V3* spare);

  std::vector<Point3> control_;
  MeshMutation m_;
  bool multithreaded_;
  std::unique_ptr<tbb::task_arena> arena_;
  std::vector<V3> a_, b_, limit_;
  std::vector<V3> base_;  // level 0, for the D-vertices' tangents (vertex_tangents.h)
  AdaptiveOutput adaptive_;
  Tessellation out_;
};

}  // namespace sdb::mipgh
