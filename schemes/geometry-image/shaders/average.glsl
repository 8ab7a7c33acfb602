// A, averaging 1/16 [1 2 1; 2 4 2; 1 2 1] of an L image, cropped by one sample on every side:
// M -> M - 2.
//
// One invocation per block of 2 rows x 4 columns of destination samples, (4x, 2y) .. (4x + 3,
// 2y + 1) as they exist (M - 2 is odd: the last block row is half a block, the last block
// column one to four columns wide). The eight 3 x 3 stencils lie in one 4 x 6 window of the
// source, 24 fetches where eight invocations take 72 (a 2 x 2 block's 4 x 4 window, until
// 2026-12-06: 32 for the same eight), and one invocation's fixed cost instead of eight. Sums as
// masks.cpp's average_pass, in its order.
#extension GL_EXT_control_flow_attributes : require
#include "gim_common.glsl"
#include "source_planes.glsl"
#define GIM_DESTINATION 1
#include "destination_planes.glsl"

// The sample of 3 x 3 stencil w[r .. r + 2][q .. q + 2] centred on w[r + 1][q + 1].
vec3 average_at(vec3 w[4][6], int r, int q) {
  precise vec3 edges = (w[r + 1][q] + w[r + 1][q + 2]) + (w[r][q + 1] + w[r + 2][q + 1]);
  precise vec3 corners = (w[r][q] + w[r + 2][q + 2]) + (w[r][q + 2] + w[r + 2][q]);
  precise vec3 v = ((4.0 * w[r + 1][q + 1] + 2.0 * edges) + corners) * 0.0625;
  return v;
}

void main() {
  uint x = gl_GlobalInvocationID.x, y = gl_GlobalInvocationID.y;
  uint s = pc.src_side, d = pc.dst_side;
  if (4u * x >= d) return;
  // Destination (c, r) is centred on source (c + 1, r + 1): the window starts at source (4x, 2y).
  // Past the last block's samples the window runs up to three columns or a row past the source;
  // those reads are clamped and feed no stored sample.
  vec3 w[4][6];
  [[unroll]] for (int r = 0; r < 4; ++r)
    [[unroll]] for (int q = 0; q < 6; ++q)
      w[r][q] = src(min(2u * y + uint(r), s - 1u) * s + min(4u * x + uint(q), s - 1u));
  uint o = 2u * y * d + 4u * x;
  bool has_below = 2u * y + 1u < d;
  [[unroll]] for (int c = 0; c < 4; ++c) {
    bool has_column = 4u * x + uint(c) < d;
    if (has_column) store(o + uint(c), average_at(w, 0, c));
    if (has_column && has_below) store(o + d + uint(c), average_at(w, 1, c));
  }
}
