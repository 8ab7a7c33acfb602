#version 450
// The regular vertices' limit (limit.cpp, project_regular): Sdc's constant masks on the ring the
// plan listed. One vertex an invocation, from pc.first (the ring table comes in views of at most
// maxTexelBufferElements, one dispatch each); special vertices skip.
#include "limit.glsl"

vec3 ring_point(uint v, uint i) { return point(texelFetch(regular_ring, int(pc.ring_size * (v - pc.first) + i)).x); }

void main() {
  const uint local = SDB_LINEAR_INVOCATION();
  if (local >= pc.count) return;
  const uint v = pc.first + local;
  if (texelFetch(regular_ring, int(pc.ring_size * local)).x == kNone) return;
  precise vec3 centre = point(v);
  precise vec3 pos, t1, t2;
  if (pc.ring_size == 8u) {
    vec3 e[4], d[4];
    for (uint i = 0u; i < 4u; ++i) e[i] = ring_point(v, i), d[i] = ring_point(v, 4u + i);
    pos = d[0] * pc.k.x + d[1] * pc.k.x + d[2] * pc.k.x + d[3] * pc.k.x + e[0] * pc.k.y + e[1] * pc.k.y +
          e[2] * pc.k.y + e[3] * pc.k.y + centre * pc.k.z;
    precise vec3 d02 = d[0] - d[2], d13 = d[1] - d[3];
    t1 = (d02 - d13) + (e[0] - e[2]) * 4.0;
    t2 = (d02 + d13) + (e[1] - e[3]) * 4.0;
  } else {
    vec3 e[6];
    for (uint i = 0u; i < 6u; ++i) e[i] = ring_point(v, i);
    const float w = pc.k.x;
    pos = e[0] * w + e[1] * w + e[2] * w + e[3] * w + e[4] * w + e[5] * w + centre * pc.k.y;
    precise vec3 d14 = e[1] - e[4], d25 = e[2] - e[5];
    t1 = (e[0] - e[3]) + (d14 - d25) * 0.5;
    t2 = (d14 + d25) * pc.k.z;
  }
  precise vec3 p = pos + pc.origin.xyz;
  store(v, p, unit_normal(t1, t2));
}
