// cpu and cpu-mt: the mesh processor on the host, one node after another (cpu) or the D-facets,
// D-edges and D-vertices of each visit in parallel on TBB (cpu-mt).
#pragma once

#include <tbb/task_arena.h>

#include <memory>
#include <vector>

#include "harness/core/scheme.h"
#include "schemes/mipgh/atlas.h"
#include "schemes/mipgh/lod.h"
#include "schemes/mipgh/primitives.h"
#include "schemes/mipgh/processor.h"
#include "schemes/mipgh/shader.h"

namespace sdb::mipgh {

class CpuMipghEvaluation final : public Evaluation {
 public:
  // `atlas`: the mesh's (build_atlas), as the size check in prepare built it.
  CpuMipghEvaluation(const ControlMesh& mesh, SubdivisionRule rule, DAtlas atlas, int depth, bool multithreaded,
                     int threads, bool project_to_limit);
  void execute() override;
  const Tessellation& result() override { return out_; }
  size_t bytes_out() const override { return out_.positions.size() * 2 * sizeof(Point3); }

 private:
  // The atlas with Far's holes marked and the edge tags, from one refiner of the mesh.
  struct Topology {
    DAtlas atlas;
    EdgeTags tags;
  };
  static Topology topology_of(const ControlMesh& mesh, SubdivisionRule rule, DAtlas atlas, int inner);
  CpuMipghEvaluation(const ControlMesh& mesh, SubdivisionRule rule, Topology topology, int depth, bool multithreaded,
                     int threads, bool project_to_limit);
  void run();

  std::vector<Point3> control_;
  float origin_[3];  // refined relative to the control box's centre: float keeps its precision
  DAtlas atlas_;
  DLoD lod_;
  EdgeTags tags_;
  std::unique_ptr<MeshShader> shader_;
  MeshProcessor processor_;
  bool multithreaded_, project_;
  std::unique_ptr<tbb::task_arena> arena_;
  // Where semi-sharp creases outlast the depth, refined to limit_depth_for and sampled at the
  // depth's grid points: level-depth node i is inner node pick_[i] (empty: the same level).
  std::vector<uint32_t> pick_;
  std::vector<V3> a_, b_, limit_;
  Tessellation out_;
};

}  // namespace sdb::mipgh
