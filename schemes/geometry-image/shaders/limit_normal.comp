#version 450
// E and the normals in one pass, reading g^k once (the paper: "perhaps the limit operation could
// also be included"); bit-identical to limit.comp then normal.comp.
#include "gim_common.glsl"
#include "source_planes.glsl"
#include "output_grid.glsl"

layout(std430, binding = 3) writeonly buffer Positions { float positions[]; };
layout(std430, binding = 4) writeonly buffer Normals { float normals[]; };

void main() {
  uint x = gl_GlobalInvocationID.x;
  if (x >= pc.dst_side) return;
  uint j = gl_GlobalInvocationID.y * pc.dst_side + x;  // in the chunk
  uint c = padded_index(x, pc.first_row + gl_GlobalInvocationID.y);
  vec3 p = limit_at(c);
  vec3 n = normal_at(c);
  positions[3u * j] = p.x;
  positions[3u * j + 1u] = p.y;
  positions[3u * j + 2u] = p.z;
  normals[3u * j] = n.x;
  normals[3u * j + 1u] = n.y;
  normals[3u * j + 2u] = n.z;
}
