#version 450
// T_s, T_t and their unit cross product at every sample of the opened grid: normals.
#include "gim_common.glsl"
#include "source_planes.glsl"
#include "output_grid.glsl"

layout(binding = 3, r32f) uniform restrict writeonly imageBuffer normals;

void main() {
  uint x = gl_GlobalInvocationID.x;
  if (x >= pc.dst_side) return;
  uint j = gl_GlobalInvocationID.y * pc.dst_side + x;  // in the chunk
  uint c = padded_index(x, pc.first_row + gl_GlobalInvocationID.y);
  vec3 n = normal_at(c);
  STORE_FLOAT3(normals, j, n);
}
