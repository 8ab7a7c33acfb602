#version 450
// Loop edge points of level d (rules.cpp, loop_edge_points): one edge an invocation.
#include "halfedge.glsl"

void main() {
  const uint e = SDB_LINEAR_INVOCATION();
  if (e >= pc.count) return;
  store(pc.vertices + e, edge_point(e, false));
}
