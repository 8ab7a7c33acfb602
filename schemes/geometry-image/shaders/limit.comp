#version 450
// E, the limit mask, at every sample of the opened grid: positions.
#include "gim_common.glsl"
#include "source_planes.glsl"
#include "output_grid.glsl"

layout(std430, binding = 3) writeonly buffer Positions { float positions[]; };

void main() {
  uint x = gl_GlobalInvocationID.x;
  if (x >= pc.dst_side) return;
  uint j = gl_GlobalInvocationID.y * pc.dst_side + x;  // in the chunk
  uint c = padded_index(x, pc.first_row + gl_GlobalInvocationID.y);
  vec3 p = limit_at(c);
  positions[3u * j] = p.x;
  positions[3u * j + 1u] = p.y;
  positions[3u * j + 2u] = p.z;
}
