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

// A vertex point's mask as coefficients of its ring's sums: the vertex, the edges' far ends, the
// faces' other corners (each scheme sums its ring its own way), and the parent's or the child's
// crease ends.
struct RuleMask {
  float vertex = 0, edges = 0, faces = 0, parent_ends = 0, child_ends = 0;
};

// One rule's mask; `smooth`: the smooth (and dart) rule's at the vertex's valence.
inline RuleMask rule_mask(int rule, bool parent, const RuleMask& smooth) {
  RuleMask k;
  if (rule == kSmoothRule || rule == kDartRule) {
    k.vertex = smooth.vertex, k.edges = smooth.edges, k.faces = smooth.faces;
  } else if (rule == kCreaseRule) {
    k.vertex = 0.75f;
    (parent ? k.parent_ends : k.child_ends) = 0.125f;
  } else {
    k.vertex = 1.0f;
  }
  return k;
}

// Sdc's ComputeVertexVertexMask: the parent's rule's mask, or where the rule changes the parent's
// weighted by parent_mask_weight plus the child's by the rest (CombineVertexVertexMasks).
inline RuleMask vertex_point_mask(const RuleMask& smooth, float parent_vs, int parent_sharp, float child_vs, int child_sharp,
                                  int transitions, float transition_sum) {
  const int prule = vertex_rule(parent_vs, parent_sharp), crule = vertex_rule(child_vs, child_sharp);
  const RuleMask parent = rule_mask(prule, true, smooth);
  if (prule == kSmoothRule || prule == kDartRule || crule == prule) return parent;
  const float pw = parent_mask_weight(transitions, transition_sum, parent_vs, child_vs);
  const float cw = 1.0f - pw;
  const RuleMask child = rule_mask(crule, false, smooth);
  RuleMask k;
  k.vertex = pw * parent.vertex + cw * child.vertex;
  k.edges = pw * parent.edges + cw * child.edges;
  k.faces = pw * parent.faces + cw * child.faces;
  k.parent_ends = pw * parent.parent_ends;
  k.child_ends = cw * child.child_ends;
  return k;
}

}  // namespace sdb::refined
