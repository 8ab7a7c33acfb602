// CpatchCpuEvaluation: the cpu and cpu-mt backends of cpatch-2pass. prepare() builds the
// CpatchTopology, the SampleGrid for rate N and the output's triangles and SurfaceCoords;
// execute() runs the per-frame passes on the current control positions: Table 1 per vertex,
// Table 2 per extraordinary quad (its c-patch record), then the evaluation per quad. Ordinary quads
// are evaluated kLanes at a time and gather Figure 6's data straight from the vertex points
// instead of streaming records through memory. cpu-mt runs each pass with tbb::parallel_for over
// independent items, so its output is bit-identical to cpu's.
#pragma once

#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>

#include <memory>
#include <vector>

#include "harness/core/scheme.h"
#include "schemes/cpatch/conversion.h"
#include "schemes/cpatch/evaluation.h"
#include "schemes/cpatch/topology.h"

namespace sdb::cpatch {

class CpatchCpuEvaluation final : public Evaluation {
 public:
  // `quads`: a closed manifold all-quad mesh (accept_mesh() output); throws InputError otherwise.
  CpatchCpuEvaluation(const ControlMesh& quads, int rate, bool multithreaded, int threads = 0);
  CpatchCpuEvaluation(const CpatchCpuEvaluation&) = delete;  // converter_ refers to topology_
  CpatchCpuEvaluation& operator=(const CpatchCpuEvaluation&) = delete;

  void execute() override;
  const Tessellation& result() override { return out_; }
  size_t bytes_out() const override;

  // Replaces the control positions (same count) for the next execute(): animation, morphing.
  void set_positions(const std::vector<Point3>& positions);

  // Internals, for tests and for checking a GPU port against the CPU.
  const CpatchTopology& topology() const { return topology_; }
  const SampleGrid& grid() const { return grid_; }
  const VertexPoints& vertex_points() const { return points_; }
  // The record of quad `quad` from the last execute(): a c-patch's as pass 1b wrote it, an
  // ordinary quad's assembled again (execute() assembles those inside the evaluation pass).
  PatchRecord record(int quad) const;
  const Tessellation& output() const { return out_; }

 private:
  void build_output_topology();
  void build_lane_groups();
  template <class Body>
  void for_range(int count, int grain, const Body& body);

  CpatchTopology topology_;
  CpatchConverter converter_;
  SampleGrid grid_;
  std::vector<Vec3f> positions_;
  VertexPoints points_;
  std::vector<Vec3f> records_;    // kRecordSize per extraordinary quad (c-patches)
  std::vector<int> lane_groups_;  // kLanes ordinary quads per group
  Tessellation out_;
  bool multithreaded_;
  std::unique_ptr<tbb::task_arena> arena_;
  PatchScratch scratch_;
  tbb::enumerable_thread_specific<PatchScratch> thread_scratch_;
};

}  // namespace sdb::cpatch
