#version 450
// T_s, T_t and their unit cross product at every sample of the opened grid: normals, four
// vertices per invocation (output_grid.glsl).
#include "gim_common.glsl"
#include "source_planes.glsl"
#include "output_grid.glsl"

layout(std430, binding = 1) restrict writeonly buffer Normals { u64vec4 normals[]; };

void main() {
  const uint t = SDB_LINEAR_INVOCATION();
  if (8u * t >= chunk_vertices()) return;
  vec3 n[8];
  [[unroll]] for (int g = 0; g < 2; ++g) {
    vec3 s[4][9];
    four_neighbourhoods(2u * t + uint(g), s);
    [[unroll]] for (int k = 0; k < 4; ++k) {
      n[4 * g + k] = normal_of(s[k]);
    }
  }
  STORE_EIGHT(normals, t, n);
}
