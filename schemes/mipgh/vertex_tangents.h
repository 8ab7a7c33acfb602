// The limit tangents of the D-vertices as weights on level 0's nodes (the input's vertices).
//
// Taken from the level the limit is projected at, as Far's masks are, a D-vertex's tangents read
// float points 2^-level of an edge apart whose rounding (an ulp of the coordinates, 6e-8 at the
// unit size the harness places meshes at) the masks divide by that spacing: at level 6, the exact
// points of catmark_single_crease's corners rounded to float alone turn the normal by 0.020 and
// 0.023 degrees (the 0.01 bound is mipgh's precision), and limit_depth_for takes that shape's
// every depth to level 6. A tangent is a fixed linear function of the vertex's level-0 ring, which
// maps onto its ring one level down by the level's rules (processor's gather_vertex: the ring's
// slots stay in order). So the level's tangent masks are composed with those rules in double, once
// in prepare, and applied to the control points, which float holds to full precision: the one
// step in double the normal needs, outside the steps' loops. (The fragments do the same for every
// limit point: schemes/fragments/net_tangents.cpp.)
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "schemes/mipgh/shader.h"  // V3, which BaseLevel holds

namespace sdb::mipgh {

class MeshProcessor;
class MeshShader;

struct BaseTangents {
  // Per D-vertex: the level its limit is projected at, whose limit tangents these are (uniform:
  // the inner depth for all; adaptive: the vertex's home). Empty: none composed.
  std::vector<uint8_t> level;
  // Per D-vertex v: terms begin[v] .. begin[v + 1] (none: the level's own masks apply), each a
  // level-0 node and its weights in T1 and T2, to be applied relative to v's own control point.
  std::vector<uint32_t> begin, node;
  std::vector<float> t1, t2;
  bool empty() const { return level.empty(); }
  bool has(int v) const { return begin[std::size_t(v) + 1] > begin[std::size_t(v)]; }
  // Whether D-vertex v projected at level sigma takes its normal from these.
  bool applies(int v, int sigma) const { return !empty() && level[std::size_t(v)] == sigma && has(v); }
  // The unit normal T1 x T2 at D-vertex v from level 0's nodes `base`.
  V3 normal(int v, const V3* base) const;
};

struct RegularPatches;
struct FacetMasks;

// What a projection reads them with: the tables and level 0's nodes, the input's control points as
// given (not moved to the origin the levels are refined about: their differences are exact).
struct BaseLevel {
  const BaseTangents& tangents;
  const V3* points;
  const RegularPatches* patches = nullptr;  // the regular D-facets' and D-edges' normals (regular_patches.h)
  const FacetMasks* masks = nullptr;         // the others' next to extraordinary vertices (facet_masks.h)
  V3 origin{0, 0, 0};  // where the levels' nodes are relative to (positions from the patches are placed so too)
};

// Every D-vertex's (in one fan of faces, with a face) tangents at its level (`level`, one per
// D-vertex) as weights on level 0.
BaseTangents compose_base_tangents(const MeshProcessor& processor, const MeshShader& shader,
                                   std::vector<uint8_t> level);

}  // namespace sdb::mipgh
