// The limit projection of a refined level: each vertex's position and the two tangents of its
// limit on its ring, the normal their unit cross product. Where Far's limit masks are the limit
// (osd-uniform's PrimvarRefiner::Limit), those; elsewhere the exact ones (exact_masks.h), on the
// side of the face the vertex's SurfaceCoord names.
//
// Most vertices of a refined level are regular and smooth (Catmull-Clark: interior, valence 4;
// Loop: valence 6; no sharp edge, no vertex sharpness), and their masks are constants: those take
// their ring's vertices from a list made with the plan (8 or 6 a vertex) and apply the constants.
// (Walking the ring through the level's twins in the frame instead was a chain of dependent loads
// per vertex: most of the cpu's frame on the sword.)
// The rest, the "special" vertices (extraordinary, creased, on a boundary: a few per base vertex
// and 2^k per base crease or boundary edge), get their masks when the plan is made, as a table of
// ring vertices and weights: Sdc's where they are the limit, exact_masks.h's elsewhere (darts,
// several sides, extraordinary creases and boundaries, semi-sharpness left at the level).
#pragma once

#include <opensubdiv/sdc/options.h>

#include <cstdint>
#include <vector>

#include "harness/core/control_mesh.h"
#include "harness/refined/face_level.h"

namespace sdb::refined {

// Special vertices and their masks: for each, entries [begin[i], begin[i + 1]): ring vertex and
// three weights (position, first tangent, second tangent), face weights first, then edges, then
// the vertex itself (PrimvarRefiner::Limit's order).
struct SpecialTable {
  std::vector<uint32_t> vertex;  // the output vertex each is written to
  std::vector<uint32_t> begin{0}, ring;
  std::vector<float> weights;
  uint32_t size() const { return static_cast<uint32_t>(vertex.size()); }
};

struct LimitPlan {
  uint32_t face_size = 4;
  uint32_t num_vertices = 0;
  // Per vertex, `ring_size` entries (8: the other ends of its edges e0..e3 counter-clockwise, then
  // the vertices opposite it in faces 0..3; 6: the edges' other ends): its regular ring, or kNone
  // first for a special vertex (or one in no face).
  uint32_t ring_size = 8;
  std::vector<uint32_t> regular_ring;
  // The special vertices on the level's rings, and those on an earlier level's (`EarlyLevel`).
  SpecialTable special, early;
};

// An earlier level of the same hierarchy, where the rules already repeat, whose points float holds
// 2^(depth - level) times finer relative to its spacing: the special vertices it has (a base vertex,
// a first step's face point) take their limit from their ring there. Taken at the last level, a
// special vertex's tangents are differences of float points 2^-depth of an edge apart, whose
// rounding the masks divide by that spacing: 0.020 degrees at depth 5 on catmark_gregory_test5's
// boundary vertices, where the exact schemes' bound is 0.01. Masks of a vertex whose rules repeat
// are the same on every level's ring (eigenvectors of its matrix; exact_masks.h composes the
// levels where they do not), so the earlier ring gives the same limit, rounded at its own spacing.
struct EarlyLevel {
  const FaceLevel* level = nullptr;
  std::vector<uint32_t> last_of;  // per vertex of the early level: its vertex at the last level
};

// The regular masks' constants as floats, for the CPU and the shader alike: Catmull-Clark face,
// edge and vertex weights of the position (1/36, 1/9, 4/9); Loop edge and vertex weights (1/12,
// 1/2) and sqrt(3)/2 of the second tangent.
struct RegularConstants {
  float k[3];
};
RegularConstants regular_constants(uint32_t face_size);

// Throws std::invalid_argument for a rule other than Catmull-Clark (quads) or Loop (triangles).
// `options`: the mesh's (harness/mesh sdc_options), whose crease method refines what sharpness is
// left.
LimitPlan plan_limit(const FaceLevel& level, SubdivisionRule rule, const OpenSubdiv::Sdc::Options& options,
                     const EarlyLevel* early = nullptr);

// Positions (plus `origin`: the levels may be refined relative to a centre) and unit normals of
// vertices [first, last) that are regular (the rest are left), and of special vertices
// [first, last) of a table: from the level's points (xyz, `stride` floats apart).
// shaders/limit.comp does the same operations in the same order.
struct Projection {
  const float* points;
  uint32_t stride;
  float origin[3];
  Point3* positions;
  Point3* normals;
  const float* early_points = nullptr;  // the early level's (plan.early), `stride` floats apart
};
void project_regular(const LimitPlan& plan, const Projection& p, uint32_t first, uint32_t last);
// Entries [first, last) of `table`, from `points`.
void project_special(const SpecialTable& table, const float* points, const Projection& p, uint32_t first, uint32_t last);

// Both, over every vertex, on this thread or on TBB's.
void project(const LimitPlan& plan, const Projection& p, bool parallel);

}  // namespace sdb::refined
