#version 450
// E, the limit mask, at every sample of the opened grid: positions, eight vertices per invocation
// (output_grid.glsl).
#include "gim_common.glsl"
#include "source_planes.glsl"
#include "output_grid.glsl"

layout(std430, binding = 1) restrict writeonly buffer Positions { vec4 positions[]; };

void main() {
  uint t;
  if (!output_block(t)) return;
  vec3 p[8];
  vec3 s[8][9];
  eight_neighbourhoods(t, s);
  [[unroll]] for (int k = 0; k < 8; ++k) {
    p[k] = limit_of(s[k]);
  }
  STORE_EIGHT(positions, t, p);
}
