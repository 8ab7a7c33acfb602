// The points of one Edge-Friend level (the paper's kernel, Listing 2, its points half): one
// invocation i computes vertex i's vertex point (i < V) and quad i's face point and the points of
// the two edges it owns (i < Q); every point is written once, no atomics, every sum in one fixed
// order, so cpu-mt equals cpu bit for bit and the shaders (shaders/edgefriend.glsl, `precise`,
// the same operations in the same order) equal both.
//
// The rules are OpenSubdiv's (the output must equal Far's uniform refinement), written as the
// paper writes them on a quad mesh, where a face point is its corners' mean:
//   face point (A + B + C + D) / 4;
//   edge point of B-C, between quad ABCD and its friend's C B B' C': 3/8 (B + C) + 1/16 (A + D)
//   + 1/16 (B' + C'), or the midpoint where both halves stay sharp, or the blend of the two by
//   the edge's sharpness s <= 1 (Sdc's edge mask);
//   vertex point: smooth (1 - 7/(4n)) V + 3/(2n^2) sum E + 1/(4n^2) sum D over the ring's edge
//   ends E and diagonals D, crease 3/4 V + 1/8 (E0 + E1), corner V; where the rule changes from
//   this level to the next, the parent's and the child's masks blended by the mean sharpness of
//   what decays (Sdc's ComputeVertexVertexMask). The paper's own vertex rule differs there
//   (README.md, "What differs").
// The first step (general faces to quads) is a stencil table (first_step.h).
#pragma once

#include <cstdint>
#include <vector>

#include "harness/core/control_mesh.h"
#include "schemes/edgefriend/topology.h"

namespace sdb::edgefriend {

// The smooth vertex mask's weights for each valence up to kMaxValence (topology.h), in float
// (tables, so that the shaders read the same bits: GLSL's division is not exact): V, sum E, sum D.
struct SmoothWeights {
  std::vector<float> vertex, edge, diagonal;
};
SmoothWeights smooth_weights();

// One level's step: level `p`'s points to the next level's (`out_index`: on the last step, the
// output's numbering, topology.h; null elsewhere).
struct Step {
  const Level* p;
  const SmoothWeights* weights;
  const Point3* src;
  Point3* dst;
  const uint32_t* out_index;
};

// Invocations [first, last) of the level's kernel (there are max(V, Q)).
void refine_points(const Step& s, uint32_t first, uint32_t last);
uint32_t invocations(const Level& p);

// The whole level, on this thread or on TBB's (one parallel loop: the paper's one kernel a level).
void refine_level_points(const Step& s, bool parallel);

}  // namespace sdb::edgefriend
