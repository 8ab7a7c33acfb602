// cpu and cpu-mt: fragments refined independently through their shape's tables, kLanes of one
// shape at a time (kernel.h); cpu-mt runs the batches in parallel on TBB, one scratch set of
// level buffers per thread.
#pragma once

#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>

#include <memory>
#include <vector>

#include "harness/core/scheme.h"
#include "schemes/fragments/kernel.h"
#include "schemes/fragments/surface.h"

namespace sdb::fragments {

class CpuFragmentEvaluation final : public Evaluation {
 public:
  CpuFragmentEvaluation(const ControlMesh& mesh, SubdivisionRule rule, int depth, bool multithreaded, int threads,
                        bool project_to_limit);
  void execute() override;
  const Tessellation& result() override { return out_; }
  size_t bytes_out() const override { return out_.positions.size() * 2 * sizeof(Point3); }
  // Its tables name slots by byte offset (address_in_bytes), as the CPU kernel reads them.
  const FragmentSurface& surface() const { return surface_; }

 private:
  struct LaneBuffers {
    std::vector<Lanes<kLanes>> a, b, net, position, normal;
  };
  struct PairBuffers {
    std::vector<PairSlot> level0, a, b;
    std::vector<Pair> position;
    std::vector<Lanes<1>> net, normal;
  };
  struct Scratch {
    LaneBuffers wide;
    PairBuffers narrow;
  };
  void run_lanes(const FragmentSurface::Batch& batch, LaneBuffers& s);
  void run_pair(uint32_t fragment, PairBuffers& s);
  void run(const FragmentSurface::Batch& batch, Scratch& s);

  std::vector<Point3> control_;
  float origin_[3];  // the control box's centre: refined relative to it, float keeps its precision
  FragmentSurface surface_;
  bool multithreaded_, project_;
  std::unique_ptr<tbb::task_arena> arena_;
  tbb::enumerable_thread_specific<Scratch> scratch_;
  Tessellation out_;
};

}  // namespace sdb::fragments
