#version 450
// E and the normals in one pass, reading g^k once (the paper: "perhaps the limit operation could
// also be included"); bit-identical to limit.comp then normal.comp. Four vertices per invocation
// (output_grid.glsl).
#include "gim_common.glsl"
#include "source_planes.glsl"
#include "output_grid.glsl"

layout(std430, binding = 1) restrict writeonly buffer Positions { u64vec2 positions[]; };
layout(std430, binding = 2) restrict writeonly buffer Normals { u64vec2 normals[]; };

void main() {
  const uint t = SDB_LINEAR_INVOCATION();
  if (4u * t >= chunk_vertices()) return;
  vec3 s[4][9], p[4], n[4];
  four_neighbourhoods(t, s);
  [[unroll]] for (int k = 0; k < 4; ++k) {
    p[k] = limit_of(s[k]);
    n[k] = normal_of(s[k]);
  }
  STORE_FOUR(positions, t, p);
  STORE_FOUR(normals, t, n);
}
