#version 450
// Catmull-Clark edge points of level d (rules.cpp, catmark_edge_points): one edge an invocation.
#include "halfedge.glsl"

void main() {
  const uint e = SDB_LINEAR_INVOCATION();
  if (e >= pc.count) return;
  store(pc.vertices + pc.faces + e, edge_point(e, true));
}
