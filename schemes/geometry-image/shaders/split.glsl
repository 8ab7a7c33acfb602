// L, splitting (Table 1): padded S -> 2S - 1. Even/even samples copy, odd/even and even/odd
// average 2, odd/odd average 4 (diagonal pairs first: a half turn swaps the members of each).
// One invocation per destination sample, as the paper's fragment program.
#include "gim_common.glsl"
#include "source_planes.glsl"
#define GIM_DESTINATION 1
#include "destination_planes.glsl"

void main() {
  uint col = parity_grouped_column(), row = gl_GlobalInvocationID.y;
  if (col >= pc.dst_side) return;
  uint i = row * pc.dst_side + col;
  uint a = (row >> 1u) * pc.src_side + (col >> 1u);  // source sample at or above-left of it
  uint b = a + pc.src_side;                          // the one below a
  precise vec3 v;
  if ((row & 1u) == 0u) {
    if ((col & 1u) == 0u) v = src(a);
    else v = 0.5 * (src(a) + src(a + 1u));
  } else {
    if ((col & 1u) == 0u) v = 0.5 * (src(a) + src(b));
    else v = 0.25 * ((src(a) + src(b + 1u)) + (src(a + 1u) + src(b)));
  }
  store(i, v);
}
