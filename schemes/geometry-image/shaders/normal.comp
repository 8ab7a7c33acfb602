#version 450
// T_s, T_t and their unit cross product at every sample of the opened grid: normals, four
// vertices per invocation (output_grid.glsl).
#include "gim_common.glsl"
#include "source_planes.glsl"
#include "output_grid.glsl"

layout(std430, binding = 1) restrict writeonly buffer Normals { vec4 normals[]; };

void main() {
  uint t;
  if (!output_block(t)) return;
  vec3 n[8];
  vec3 s[8][9];
  eight_neighbourhoods(t, s);
  [[unroll]] for (int k = 0; k < 8; ++k) {
    n[k] = normal_of(s[k]);
  }
  STORE_EIGHT(normals, t, n);
}
