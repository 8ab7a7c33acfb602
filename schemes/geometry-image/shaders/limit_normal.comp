#version 450
// E and the normals in one pass, reading g^k once (the paper: "perhaps the limit operation could
// also be included"); bit-identical to limit.comp then normal.comp. Eight vertices per invocation
// (output_grid.glsl).
#include "gim_common.glsl"
#include "source_planes.glsl"
#include "output_grid.glsl"

layout(std430, binding = 1) restrict writeonly buffer Positions { vec4 positions[]; };
layout(std430, binding = 2) restrict writeonly buffer Normals { vec4 normals[]; };

void main() {
  uint t;
  if (!output_block(t)) return;
  vec3 p[8], n[8];
  vec3 s[8][9];
  eight_neighbourhoods(t, s);
  [[unroll]] for (int k = 0; k < 8; ++k) {
    p[k] = limit_of(s[k]);
    n[k] = normal_of(s[k]);
  }
  STORE_EIGHT(positions, t, p);
  STORE_EIGHT(normals, t, n);
}
