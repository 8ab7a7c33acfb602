// The vertex refinement of one level, gathered per new point (the papers' "Gather" routines,
// HPG 2021 Section 5 / Listing 2; the deterministic form: no atomics, every sum in one fixed
// order), with OpenSubdiv's masks so that the points equal Far's uniform refinement:
//   Catmull-Clark: face points (the face's corners), edge points (Sdc's edge mask: smooth, crease,
//   or the crease-to-smooth blend by the edge's sharpness), vertex points (Sdc's vertex-vertex
//   mask on the halfedge ring, the parent's and the child's rule blended by the fractional weight
//   where sharpness decays);
//   Loop: edge points and vertex points the same way.
// Level d + 1's points are [vertex points, (Catmull-Clark) face points, edge points]
// (topology.h). shaders/*.comp do the same operations in the same order.
#pragma once

#include <cstdint>
#include <vector>

#include "harness/core/control_mesh.h"
#include "schemes/halfedge/topology.h"

namespace sdb::halfedge {

// Sdc's smooth vertex mask for each valence up to kMaxValence, in float as Far computes it:
// Catmull-Clark (n - 2) / n and 1 / n^2 (edges and faces alike), Loop 1 - n w and w; and 1 / n,
// the face mask. Tables, so that the shaders read the same bits (GLSL's division is not exact).
constexpr int kMaxValence = 1024;
struct SmoothWeights {
  std::vector<float> vertex, ring, inverse;
};
SmoothWeights smooth_weights(SubdivisionRule rule);

// One level's step over a range of the new points, from level `p`'s points to level `c`'s
// (`creased`: p has sharpness, boundaries included, so the crease rules apply).
struct Step {
  const Level* p;
  const Level* c;
  const SmoothWeights* weights;
  bool creased;
  const Point3* src;  // level p
  Point3* dst;        // level c
};

void catmark_face_points(const Step& s, uint32_t first, uint32_t last);
void catmark_edge_points(const Step& s, uint32_t first, uint32_t last);
void catmark_vertex_points(const Step& s, uint32_t first, uint32_t last);
void loop_edge_points(const Step& s, uint32_t first, uint32_t last);
void loop_vertex_points(const Step& s, uint32_t first, uint32_t last);

// A level's whole step, on this thread or on TBB's (each pass a parallel loop, in this order).
void refine_points(const Step& s, SubdivisionRule rule, bool parallel);

}  // namespace sdb::halfedge
