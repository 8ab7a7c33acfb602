// pad: g0's control positions -> padded g^0, through the gather table (padded index -> g0 vertex,
// masks.h padding_gather_table). One invocation per padded sample.
#include "gim_common.glsl"

layout(std430, binding = 0) readonly buffer Gather { int gather[]; };
layout(std430, binding = 1) readonly buffer Control { float control[]; };  // Point3 per g0 vertex
#define GIM_DESTINATION 2
#include "destination_planes.glsl"

void main() {
  uint col = gl_GlobalInvocationID.x, row = gl_GlobalInvocationID.y;
  if (col >= pc.dst_side) return;
  uint i = row * pc.dst_side + col;
  uint v = 3u * uint(gather[i]);
  store(i, vec3(control[v], control[v + 1u], control[v + 2u]));
}
