#version 450
// E and the normals in one pass, reading g^k once (the paper: "perhaps the limit operation could
// also be included"); bit-identical to limit.comp then normal.comp.
#include "gim_common.glsl"
#include "source_planes.glsl"
#include "output_grid.glsl"

layout(binding = 3, r32f) uniform restrict writeonly imageBuffer positions;
layout(binding = 4, r32f) uniform restrict writeonly imageBuffer normals;

void main() {
  uint x = gl_GlobalInvocationID.x;
  if (x >= pc.dst_side) return;
  uint j = gl_GlobalInvocationID.y * pc.dst_side + x;  // in the chunk
  uint c = padded_index(x, pc.first_row + gl_GlobalInvocationID.y);
  vec3 p = limit_at(c);
  vec3 n = normal_at(c);
  STORE_FLOAT3(positions, j, p);
  STORE_FLOAT3(normals, j, n);
}
