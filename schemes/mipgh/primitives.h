// Primitive compilation (Figure 8): a level's nodes as the harness's tessellation, and the
// sampling of a shallower level's grid points on a deeper one.
#pragma once

#include <cstdint>
#include <utility>
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

// Adaptive primitive compilation (Figure 8 over Figure 13's labels): D-facet f drawn at level
// render[f]. A node shared by D-facets drawn at different levels (on a D-edge, at a D-vertex) is
// one output node, taken from the finest of them; a coarser D-facet's micro-facets along such a
// D-edge fan out to every node the finer one has there, so no crack and no T-junction opens.
// A node drawn at level l comes from level home[l] (the DLoD's labels are home[render]), deeper
// where semi-sharp creases outlast l (MeshMutation::home). Says, per level, which nodes are output
// there (`nodes`: level node, output node) and what to project there (`homes`).
struct AdaptiveOutput {
  std::vector<LevelHomes> homes;
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> nodes;
};
AdaptiveOutput compile_adaptive(const DAtlas& atlas, const DLoD& lod, const std::vector<uint8_t>& render,
                                const std::vector<uint8_t>& home, Tessellation& out);

// Adaptive: the level each D-vertex's output node comes from, home[] of the finest level a D-facet
// at it is drawn at (every D-facet at it, not only its ring's: a vertex of several fans has the
// first in its ring).
std::vector<uint8_t> vertex_homes(const DAtlas& atlas, const std::vector<uint8_t>& render,
                                  const std::vector<uint8_t>& home);

// For each node of level sigma, the node of the deeper level `inner` at the same grid point.
std::vector<uint32_t> same_points_at(const DAtlas& atlas, const DLoD& lod, int sigma, int inner);

}  // namespace sdb::mipgh
