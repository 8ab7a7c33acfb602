// Primitive compilation (Figure 8): a level's nodes as the harness's tessellation, and the
// sampling of a shallower level's grid points on a deeper one.
#pragma once

#include <cstdint>
#include <vector>

#include "harness/core/tessellation.h"
#include "schemes/mipgh/atlas.h"
#include "schemes/mipgh/lod.h"

namespace sdb::mipgh {

// Primitive compilation at level sigma: two triangles per micro-facet of every quad D-facet that
// is not a hole (one per micro-triangle of a triangle), and each node's SurfaceCoord in the
// D-facet that owns it (interior: its own; D-edge: the major halfedge's; D-vertex: the first of
// its ring), in OpenSubdiv's (u, v) of that face.
void compile_primitives(const DAtlas& atlas, const DLoD& lod, int sigma, Tessellation& out);

// For each node of level sigma, the node of the deeper level `inner` at the same grid point.
std::vector<uint32_t> same_points_at(const DAtlas& atlas, const DLoD& lod, int sigma, int inner);

}  // namespace sdb::mipgh
