#version 450
// The regular vertices' limit (limit.cpp, project_regular): Sdc's constant masks on the ring,
// walked from the vertex's corner. One vertex an invocation; special vertices skip.
#include "limit.glsl"

uint next_corner(uint c) {
  const uint i = c % pc.face_size;
  return c - i + (i + 1u == pc.face_size ? 0u : i + 1u);
}
uint prev_corner(uint c) {
  const uint i = c % pc.face_size;
  return c - i + (i == 0u ? pc.face_size - 1u : i - 1u);
}

void main() {
  const uint v = SDB_LINEAR_INVOCATION();
  if (v >= pc.count) return;
  uint c = texelFetch(regular_corner, int(v)).x;
  if (c == kNone) return;
  precise vec3 centre = point(v);
  precise vec3 pos, t1, t2;
  if (pc.face_size == 4u) {
    vec3 e[4], d[4];
    for (int i = 0; i < 4; ++i) {
      const uint nc = next_corner(c);
      e[i] = point(texelFetch(verts, int(nc)).x);
      d[i] = point(texelFetch(verts, int(next_corner(nc))).x);
      c = texelFetch(twin, int(prev_corner(c))).x;
    }
    pos = d[0] * pc.k.x + d[1] * pc.k.x + d[2] * pc.k.x + d[3] * pc.k.x + e[0] * pc.k.y + e[1] * pc.k.y +
          e[2] * pc.k.y + e[3] * pc.k.y + centre * pc.k.z;
    precise vec3 d02 = d[0] - d[2], d13 = d[1] - d[3];
    t1 = (d02 - d13) + (e[0] - e[2]) * 4.0;
    t2 = (d02 + d13) + (e[1] - e[3]) * 4.0;
  } else {
    vec3 e[6];
    for (int i = 0; i < 6; ++i) {
      e[i] = point(texelFetch(verts, int(next_corner(c))).x);
      c = texelFetch(twin, int(prev_corner(c))).x;
    }
    const float w = pc.k.x;
    pos = e[0] * w + e[1] * w + e[2] * w + e[3] * w + e[4] * w + e[5] * w + centre * pc.k.y;
    precise vec3 d14 = e[1] - e[4], d25 = e[2] - e[5];
    t1 = (e[0] - e[3]) + (d14 - d25) * 0.5;
    t2 = (d14 + d25) * pc.k.z;
  }
  precise vec3 p = pos + pc.origin.xyz;
  store(v, p, unit_normal(t1, t2));
}
