// The vertex point's rule as OpenSubdiv decides it, for the uniform-refinement peers' gathers
// (schemes/halfedge, schemes/edgefriend): the rule of a level from its sharp edges and vertex
// sharpness, and, where the rule changes from a level to the next, the weight of the parent's mask
// in the blend. shaders/vertex_rule.glsl is the same, operation for operation.
#pragma once

namespace sdb::refined {

// Sdc::Crease::Rule, as DetermineVertexVertexRule gives it.
enum VertexRule : int { kSmoothRule = 1, kDartRule = 2, kCreaseRule = 4, kCornerRule = 8 };
inline int vertex_rule(float vertex_sharpness, int sharp_edges) {
  if (vertex_sharpness > 0.0f || sharp_edges > 2) return kCornerRule;
  return 1 << sharp_edges;
}

// Crease::ComputeFractionalWeightAtVertex: the mean sharpness of what decays to smooth (the
// `transitions` edges of sharpness summing to `transition_sum`, and the vertex's own), at most 1.
inline float parent_mask_weight(int transitions, float transition_sum, float parent_vs, float child_vs) {
  int count = transitions;
  float sum = transition_sum;
  if (parent_vs > 0.0f && child_vs <= 0.0f) ++count, sum = sum + parent_vs;
  const float pw = count == 0 ? 0.0f : sum / float(count);
  return pw > 1.0f ? 1.0f : pw;
}

}  // namespace sdb::refined
