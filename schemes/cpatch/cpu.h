// CpatchCpuEvaluation: the cpu and cpu-mt backends of cpatch-2pass. prepare() builds the
// CpatchTopology, the SampleGrid for rate N and the output's triangles and SurfaceCoords;
// execute() runs the three per-frame passes (Table 1 per vertex, Table 2 / Figure 6 per quad,
// evaluation per quad) on the current control positions. cpu-mt runs each pass with
// tbb::parallel_for over independent items, so its output is bit-identical to cpu's.
#pragma once

#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>

#include <memory>
#include <vector>

#include "conversion.h"
#include "evaluation.h"
#include "scheme.h"
#include "topology.h"

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
  const Vec3f* record(int quad) const { return &records_[static_cast<size_t>(quad) * kRecordSize]; }
  const Tessellation& output() const { return out_; }

 private:
  void build_output_topology();
  template <class Body>
  void for_range(int count, int grain, const Body& body);

  CpatchTopology topology_;
  CpatchConverter converter_;
  SampleGrid grid_;
  std::vector<Vec3f> positions_;
  VertexPoints points_;
  std::vector<Vec3f> records_;
  Tessellation out_;
  bool multithreaded_;
  std::unique_ptr<tbb::task_arena> arena_;
  PatchScratch scratch_;
  tbb::enumerable_thread_specific<PatchScratch> thread_scratch_;
};

}  // namespace sdb::cpatch
