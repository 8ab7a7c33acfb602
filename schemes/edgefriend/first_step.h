// The first Catmull-Clark step, from the mesh's faces of any size to Edge-Friend's level 1: a
// stencil table (OpenSubdiv's Far::StencilTableFactory, made once in prepare() with the
// topology), applied each frame by the scheme's own gather (cpu loop, compute shader). The paper
// does this step in its CPU preprocessing; here it is part of every frame and of the depth, as
// the paper counts it. One row per level-1 vertex (OpenSubdiv's numbering, then the ghost face
// points: the mean of their loop's corners).
#pragma once

#include <cstdint>
#include <vector>

#include <opensubdiv/far/topologyRefiner.h>

#include "harness/core/control_mesh.h"
#include "schemes/edgefriend/topology.h"

namespace sdb::edgefriend {

struct StencilTable {
  std::vector<uint32_t> begin{0};  // rows + 1
  std::vector<uint32_t> source;
  std::vector<float> weight;
  uint32_t rows() const { return uint32_t(begin.size() - 1); }
};

StencilTable first_step(const OpenSubdiv::Far::TopologyRefiner& level1, const Hierarchy& h);

// Rows [first, last): dst[out_index ? out_index[r] : r] = sum of weight * src[source], in order
// (an out_index of kNone: not written).
void apply_stencils(const StencilTable& t, const Point3* src, Point3* dst, const uint32_t* out_index, uint32_t first,
                    uint32_t last);

}  // namespace sdb::edgefriend
