#version 450
// E, the limit mask, at every sample of the opened grid: positions.
#include "gim_common.glsl"
#include "source_planes.glsl"
#include "output_grid.glsl"

layout(binding = 3, r32f) uniform restrict writeonly imageBuffer positions;

void main() {
  uint x = gl_GlobalInvocationID.x;
  if (x >= pc.dst_side) return;
  uint j = gl_GlobalInvocationID.y * pc.dst_side + x;  // in the chunk
  uint c = padded_index(x, pc.first_row + gl_GlobalInvocationID.y);
  vec3 p = limit_at(c);
  STORE_FLOAT3(positions, j, p);
}
