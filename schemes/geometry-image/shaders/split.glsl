// L, splitting (Table 1): padded S -> 2S - 1. Even/even samples copy, odd/even and even/odd
// average 2, odd/odd average 4 (diagonal pairs first: a half turn swaps the members of each).
//
// One invocation per source sample (a, b), a, b in [0, S - 1], writing the 2 x 2 block of
// destination samples at (2a, 2b) .. (2a + 1, 2b + 1) that exist (the last source row and column
// have no odd neighbour). The paper's fragment program is one per destination sample; here its
// four parities would each take a branch, and SIMD hardware (and lavapipe, which runs every
// branch under a mask) would pay for all four at every sample. The block reads the four source
// samples once and branches on nothing but the image's edge. Sums as masks.cpp's split_pass.
#include "gim_common.glsl"
#include "source_planes.glsl"
#define GIM_DESTINATION 1
#include "destination_planes.glsl"

void main() {
  uint a = gl_GlobalInvocationID.x, b = gl_GlobalInvocationID.y;
  uint s = pc.src_side, d = pc.dst_side;
  if (a >= s) return;
  // Past the last column or row the reads are clamped; their results are not stored.
  uint right = min(a + 1u, s - 1u), below = min(b + 1u, s - 1u);
  vec3 p00 = src(b * s + a), p10 = src(b * s + right);
  vec3 p01 = src(below * s + a), p11 = src(below * s + right);
  precise vec3 row_edge = 0.5 * (p00 + p10);
  precise vec3 column_edge = 0.5 * (p00 + p01);
  precise vec3 face = 0.25 * ((p00 + p11) + (p10 + p01));
  uint o = 2u * b * d + 2u * a;
  bool has_right = a + 1u < s, has_below = b + 1u < s;
  store(o, p00);
  if (has_right) store(o + 1u, row_edge);
  if (has_below) store(o + d, column_edge);
  if (has_right && has_below) store(o + d + 1u, face);
}
