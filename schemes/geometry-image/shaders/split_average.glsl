// L and A in one pass (the paper's wish for GPUs with more texture reads): the bicubic B-spline
// subdivision masks, padded S -> 2S - 3, equal to A[L[.]] up to rounding.
//
// One invocation per source sample (a, b), a, b in [0, S - 2], writing the 2 x 2 block of g^{k+1}
// that belongs to it: destination (col, row) is L sample (col + 1, row + 1), so
//   (2a,     2b    )  the face between (a, b) and (a + 1, b + 1)       1/4  [1 1]^T [1 1]
//   (2a - 1, 2b    )  the edge on column a between rows b and b + 1    1/16 [1 1]^T [1 6 1]
//   (2a,     2b - 1)  the edge on row b between columns a and a + 1    1/16 [1 6 1]^T [1 1]
//   (2a - 1, 2b - 1)  the vertex (a, b)                                1/64 [1 6 1]^T [1 6 1]
// (the last three for a >= 1, b >= 1 as they exist). All four read the 3 x 3 samples around
// (a, b), loaded once; no invocation branches on the parity of its output, which SIMD hardware
// (and lavapipe, which runs every branch under a mask) would pay for. Every sum is masks.cpp's
// split_average_row's, in its order.
#include "gim_common.glsl"
#include "source_planes.glsl"
#define GIM_DESTINATION 1
#include "destination_planes.glsl"

void main() {
  uint a = gl_GlobalInvocationID.x, b = gl_GlobalInvocationID.y;
  uint s = pc.src_side, d = pc.dst_side;
  if (a + 2u > s) return;
  // Columns a - 1, a, a + 1 of rows b - 1 (u), b (m), b + 1 (w). Column and row -1 are read as 0
  // (clamped) only for outputs that do not exist.
  uint am = max(a, 1u) - 1u, bm = max(b, 1u) - 1u;
  uint ur = bm * s, mr = b * s, wr = (b + 1u) * s;
  vec3 u0 = src(ur + am), u1 = src(ur + a), u2 = src(ur + a + 1u);
  vec3 m0 = src(mr + am), m1 = src(mr + a), m2 = src(mr + a + 1u);
  vec3 w0 = src(wr + am), w1 = src(wr + a), w2 = src(wr + a + 1u);

  precise vec3 face = ((m1 + w2) + (m2 + w1)) * 0.25;
  store(2u * b * d + 2u * a, face);
  if (a >= 1u) {
    precise vec3 centre = m1 + w1;
    precise vec3 corners = (m0 + w2) + (m2 + w0);
    precise vec3 column_edge = (6.0 * centre + corners) * 0.0625;
    store(2u * b * d + 2u * a - 1u, column_edge);
  }
  if (b >= 1u) {
    precise vec3 centre = m1 + m2;
    precise vec3 corners = (u1 + w2) + (u2 + w1);
    precise vec3 row_edge = (6.0 * centre + corners) * 0.0625;
    store((2u * b - 1u) * d + 2u * a, row_edge);
  }
  if (a >= 1u && b >= 1u) {
    precise vec3 edges = (m0 + m2) + (u1 + w1);
    precise vec3 corners = (u0 + w2) + (u2 + w0);
    precise vec3 vertex = ((36.0 * m1 + 6.0 * edges) + corners) * 0.015625;
    store((2u * b - 1u) * d + 2u * a - 1u, vertex);
  }
}
