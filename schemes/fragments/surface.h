// A mesh prepared for fragment refinement: its partition, the pattern tables of every shape,
// where each fragment's output block starts, and the output's triangles and SurfaceCoords.
#pragma once

#include <vector>

#include "harness/core/tessellation.h"
#include "harness/mesh/osd_topology.h"
#include "schemes/fragments/fragments.h"
#include "schemes/fragments/net.h"
#include "schemes/fragments/tables.h"

namespace sdb::fragments {

struct FragmentSurface {
  FragmentSurface(const ControlMesh& mesh, SubdivisionRule rule, int depth, int inner_depth);

  SubdivisionRule rule;
  int depth;
  // Refined this far, then sampled at `depth`'s grid: far enough that no semi-sharp crease is
  // left, which Far's limit masks would take as infinitely sharp (limit_depth_for).
  int inner_depth;
  Partition partition;
  std::vector<ShapeTables> tables;  // per shape
  std::vector<size_t> first_vertex;  // per fragment: its first output vertex
  // Fragments grouped by shape, and cut into batches of at most kLanes of one shape: the unit
  // the kernel runs (kernel.h), in this order, so a shape's tables stay in cache.
  std::vector<uint32_t> order;
  struct Batch {
    uint32_t begin, count;  // into `order`
  };
  std::vector<Batch> batches;  // batches_of(kLanes), the CPU kernel's
  std::vector<Batch> batches_of(uint32_t max_count) const;
  uint32_t max_slots = 0, max_limit_entries = 0;
  size_t num_output_vertices = 0;

  // Triangles and coords of the whole output (one block per owned face).
  void describe(Tessellation& out) const;
  FragmentStats stats() const;
};

int inner_depth_for(const ControlMesh& mesh, int depth);

// The faces of the shapes' nets refined to the inner depth past which their tables are refused
// up front: the pawn's 10 shapes, 113 faces, at level 6 (463 k) took 250 MB and 5 s to build,
// catmark_gregory_test7's 11, 70 faces, at level 9 (18 M) 1 GB and 33 s.
constexpr double kMaxInnerFaces = 1 << 22;

// Output size before anything is built, for the size check in prepare.
size_t output_vertices(const ControlMesh& mesh, SubdivisionRule rule, int depth);

}  // namespace sdb::fragments
