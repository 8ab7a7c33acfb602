#version 450
// E, the limit mask, at every sample of the opened grid: positions, four vertices per invocation
// (output_grid.glsl).
#include "gim_common.glsl"
#include "source_planes.glsl"
#include "output_grid.glsl"

layout(std430, binding = 1) restrict writeonly buffer Positions { u64vec2 positions[]; };

void main() {
  const uint t = SDB_LINEAR_INVOCATION();
  if (4u * t >= chunk_vertices()) return;
  vec3 s[4][9], p[4];
  four_neighbourhoods(t, s);
  [[unroll]] for (int k = 0; k < 4; ++k) p[k] = limit_of(s[k]);
  STORE_FOUR(positions, t, p);
}
