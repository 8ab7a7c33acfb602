#version 450
// Catmull-Clark face points of level d (rules.cpp, catmark_face_points): one face an invocation.
#include "halfedge.glsl"

void main() {
  const uint f = SDB_LINEAR_INVOCATION();
  if (f >= pc.count) return;
  const uint a = pc.face_size != 0u ? f * pc.face_size : texelFetch(base, int(pc.base_first + f)).x;
  const uint n = pc.face_size != 0u ? pc.face_size : texelFetch(base, int(pc.base_first + f + 1u)).x - a;
  precise vec3 sum = point(vert(a));
  for (uint i = 1u; i < n; ++i) sum = sum + point(vert(a + i));
  precise vec3 p = sum * texelFetch(weights, int(2u * kTable + n)).x;
  store(pc.vertices + f, p);
}
