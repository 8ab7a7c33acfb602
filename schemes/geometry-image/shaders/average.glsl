// A, averaging 1/16 [1 2 1; 2 4 2; 1 2 1] of an L image, cropped by one sample on every side:
// M -> M - 2. One invocation per destination sample.
#include "gim_common.glsl"
#include "source_planes.glsl"
#define GIM_DESTINATION 1
#include "destination_planes.glsl"

void main() {
  uint col = gl_GlobalInvocationID.x, row = gl_GlobalInvocationID.y;
  if (col >= pc.dst_side) return;
  uint i = row * pc.dst_side + col;
  uint s = pc.src_side;
  uint c = (row + 1u) * s + (col + 1u);
  precise vec3 edges = (src(c - 1u) + src(c + 1u)) + (src(c - s) + src(c + s));
  precise vec3 corners = (src(c - s - 1u) + src(c + s + 1u)) + (src(c - s + 1u) + src(c + s - 1u));
  precise vec3 v = ((4.0 * src(c) + 2.0 * edges) + corners) * 0.0625;
  store(i, v);
}
