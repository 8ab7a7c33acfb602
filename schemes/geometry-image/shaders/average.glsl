// A, averaging 1/16 [1 2 1; 2 4 2; 1 2 1] of an L image, cropped by one sample on every side:
// M -> M - 2.
//
// One invocation per 2 x 2 block of destination samples, (2x, 2y) .. (2x + 1, 2y + 1) as they
// exist (M - 2 is odd: the last block column and row are half blocks). The four 3 x 3 stencils
// lie in one 4 x 4 window of the source, 16 fetches where four invocations take 36, and one
// invocation's fixed cost instead of four. Sums as masks.cpp's average_pass, in its order.
#extension GL_EXT_control_flow_attributes : require
#include "gim_common.glsl"
#include "source_planes.glsl"
#define GIM_DESTINATION 1
#include "destination_planes.glsl"

// The sample of 3 x 3 stencil w[r + 1 .. r + 3][q + 1 .. q + 3] centred on w[r + 1][q + 1].
vec3 average_at(vec3 w[4][4], int r, int q) {
  precise vec3 edges = (w[r + 1][q] + w[r + 1][q + 2]) + (w[r][q + 1] + w[r + 2][q + 1]);
  precise vec3 corners = (w[r][q] + w[r + 2][q + 2]) + (w[r][q + 2] + w[r + 2][q]);
  precise vec3 v = ((4.0 * w[r + 1][q + 1] + 2.0 * edges) + corners) * 0.0625;
  return v;
}

void main() {
  uint x = gl_GlobalInvocationID.x, y = gl_GlobalInvocationID.y;
  uint s = pc.src_side, d = pc.dst_side;
  if (2u * x >= d) return;
  // Destination (c, r) is centred on source (c + 1, r + 1): the window starts at source (2x, 2y).
  // The half blocks' window runs one column or row past the source; those reads are clamped and
  // feed no stored sample.
  vec3 w[4][4];
  [[unroll]] for (int r = 0; r < 4; ++r)
    [[unroll]] for (int q = 0; q < 4; ++q)
      w[r][q] = src(min(2u * y + uint(r), s - 1u) * s + min(2u * x + uint(q), s - 1u));
  uint o = 2u * y * d + 2u * x;
  bool has_right = 2u * x + 1u < d, has_below = 2u * y + 1u < d;
  store(o, average_at(w, 0, 0));
  if (has_right) store(o + 1u, average_at(w, 0, 1));
  if (has_below) store(o + d, average_at(w, 1, 0));
  if (has_right && has_below) store(o + d + 1u, average_at(w, 1, 1));
}
