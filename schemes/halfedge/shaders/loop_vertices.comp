#version 450
// Loop vertex points of level d (rules.cpp, loop_vertex_points): one vertex an invocation.
#include "halfedge.glsl"

void main() {
  const uint v = SDB_LINEAR_INVOCATION();
  if (v >= pc.count) return;
  vertex_point(v, false);
}
