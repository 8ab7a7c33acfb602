// The limit projection of a refined level with Far's limit masks, as osd-uniform's
// PrimvarRefiner::Limit applies them: each vertex's position and the two tangents of Sdc's
// ComputeVertexLimitMask on its ring, the normal their unit cross product.
//
// Most vertices of a refined level are regular and smooth (Catmull-Clark: interior, valence 4;
// Loop: valence 6; no sharp edge but at most one, no vertex sharpness), and their masks are
// constants: those take their ring's vertices from a list made with the plan (8 or 6 a vertex)
// and apply the constants. (Walking the ring through the level's twins in the frame instead was
// a chain of dependent loads per vertex: most of the cpu's frame on the sword.)
// The rest, the "special" vertices (extraordinary, creased, on a boundary: a few per base vertex
// and 2^k per base crease or boundary edge), get their masks from Sdc itself when the plan is made,
// as a table of ring vertices and weights. Where sharpness is left at the level (a semi-sharp
// crease that outlasts the depth) Far's masks take it as infinitely sharp, and so does this.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "harness/core/control_mesh.h"
#include "harness/refined/face_level.h"

namespace sdb::refined {

struct LimitPlan {
  uint32_t face_size = 4;
  uint32_t num_vertices = 0;
  // Per vertex, `ring_size` entries (8: the other ends of its edges e0..e3 counter-clockwise, then
  // the vertices opposite it in faces 0..3; 6: the edges' other ends): its regular ring, or kNone
  // first for a special vertex (or one in no face).
  uint32_t ring_size = 8;
  std::vector<uint32_t> regular_ring;
  // The special vertices, and for each its entries [begin[i], begin[i + 1]): ring vertex and three
  // weights (position, first tangent, second tangent), face weights first, then edges, then the
  // vertex itself (PrimvarRefiner::Limit's order).
  std::vector<uint32_t> special, begin{0}, ring;
  std::vector<float> weights;
  // Vertices of the level where an edge or the vertex is still semi-sharp (0 < s < 10): Far's
  // masks there are not the limit (harness/conformance/far_oracle.h, far_limit_is_exact).
  uint64_t semi_sharp_vertices = 0;
  float largest_sharpness_left = 0;  // below infinite
};

// The regular masks' constants as floats, for the CPU and the shader alike: Catmull-Clark face,
// edge and vertex weights of the position (1/36, 1/9, 4/9); Loop edge and vertex weights (1/12,
// 1/2) and sqrt(3)/2 of the second tangent.
struct RegularConstants {
  float k[3];
};
RegularConstants regular_constants(uint32_t face_size);

// The note a row carries where a semi-sharp crease outlasts the depth: Far's limit masks, which
// the projection applies, take the sharpness left as infinite there, so the projected points are
// not on the limit surface. As Evaluation::notes() carries it: none where no sharpness is left.
std::vector<std::string> semi_sharp_notes(const LimitPlan& plan, int depth);

// Throws std::invalid_argument for a rule other than Catmull-Clark (quads) or Loop (triangles).
LimitPlan plan_limit(const FaceLevel& level, SubdivisionRule rule);

// Positions (plus `origin`: the levels may be refined relative to a centre) and unit normals of
// vertices [first, last) that are regular (the rest are left), and of special vertices
// [first, last) of plan.special: from the level's points (xyz, `stride` floats apart).
// shaders/limit.comp does the same operations in the same order.
struct Projection {
  const float* points;
  uint32_t stride;
  float origin[3];
  Point3* positions;
  Point3* normals;
};
void project_regular(const LimitPlan& plan, const Projection& p, uint32_t first, uint32_t last);
void project_special(const LimitPlan& plan, const Projection& p, uint32_t first, uint32_t last);

// Both, over every vertex, on this thread or on TBB's.
void project(const LimitPlan& plan, const Projection& p, bool parallel);

}  // namespace sdb::refined
