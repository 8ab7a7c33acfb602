// Conway's game of life as a mesh shader (Figure 23): repeated adjustment without refinement on
// the nodes of a Catmull-Clark-subdivided mesh, each node's neighbours its 1-disk (the direct
// and diagonal ones: a regular node has Conway's eight). Rule B3/S23.
#pragma once

#include <vector>

#include "harness/core/control_mesh.h"
#include "harness/core/scheme.h"
#include "schemes/mipgh/shader.h"

namespace sdb::mipgh {

// The states of every node of `mesh` (quads) refined `depth` times, one generation after another,
// on the cpu (MeshProcessor::adjust) or a Vulkan device (life_vulkan.h, the same 1-disks).
class LifeOnMesh {
 public:
  // Throws Unsupported for Backend::Vulkan without a device.
  LifeOnMesh(const ControlMesh& quads, int depth, Backend backend = Backend::Cpu);
  ~LifeOnMesh();
  // Sets the nodes of D-facet f's interior at (row, column) = (top + i, left + j) for each 'O' of
  // pattern row i, column j.
  void place(int facet, int top, int left, const std::vector<const char*>& pattern);
  void step();
  const std::vector<V3>& state() const;  // x = 1: alive
  int facet_side() const;                // nodes along a D-facet's side at the depth
  int num_facets() const;

 private:
  struct Impl;
  Impl* impl_;
};

// The period-3 pulsar, 13 x 13.
const std::vector<const char*>& pulsar();

}  // namespace sdb::mipgh
