#version 450
// The special vertices' limit (limit.cpp, project_special): Sdc's masks from the plan's table,
// summed in its order. One special vertex an invocation.
#include "limit.glsl"

void main() {
  const uint i = SDB_LINEAR_INVOCATION();
  if (i >= pc.count) return;
  precise vec3 pos = vec3(0.0), t1 = vec3(0.0), t2 = vec3(0.0);
  const uint first = texelFetch(begin, int(i)).x, last = texelFetch(begin, int(i + 1u)).x;
  for (uint k = first; k < last; ++k) {
    const vec3 p = point(texelFetch(ring, int(k)).x);
    pos = pos + p * texelFetch(weights, int(3u * k)).x;
    t1 = t1 + p * texelFetch(weights, int(3u * k + 1u)).x;
    t2 = t2 + p * texelFetch(weights, int(3u * k + 2u)).x;
  }
  precise vec3 q = pos + pc.origin.xyz;
  store(texelFetch(special, int(i)).x, q, unit_normal(t1, t2));
}
