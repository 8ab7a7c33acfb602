#include "schemes/mipgh/tile.h"

#include <cmath>

namespace sdb::mipgh::tile {

// The tile's loops in AVX2 lanes where the CPU has them, SSE2 otherwise (as the fragments' kernel).
#define SDB_TILE_CLONES __attribute__((target_clones("avx2", "default")))

// Figure 20's stencils at every square of one coordinate's plane: vertex points (class 0),
// horizontal edge points (1), vertical ones (2), facet points (3).
SDB_TILE_CLONES void quad_classes(const float* __restrict P, int n, float* __restrict vv, float* __restrict eh,
                  float* __restrict ev, float* __restrict fv) {
  for (int L = 0; L < n * n; ++L) {
    vv[L] = 0.5625f * P[L] + 0.09375f * ((P[L + 1] + P[L - 1]) + (P[L + n] + P[L - n])) +
            0.015625f * ((P[L + n + 1] + P[L - n - 1]) + (P[L + n - 1] + P[L - n + 1]));
    eh[L] = 0.375f * (P[L] + P[L + 1]) + 0.0625f * ((P[L - n] + P[L - n + 1]) + (P[L + n] + P[L + n + 1]));
    ev[L] = 0.375f * (P[L] + P[L + n]) + 0.0625f * ((P[L - 1] + P[L + n - 1]) + (P[L + 1] + P[L + n + 1]));
    fv[L] = 0.25f * ((P[L] + P[L + n + 1]) + (P[L + 1] + P[L + n]));
  }
}

// Loop's, in a triangle's square: vertex points (class 0), edge points of (a, b)-(a, b+1) (1),
// (a, b)-(a+1, b) (2) and the diagonal (a, b+1)-(a+1, b) (3).
SDB_TILE_CLONES void triangle_classes(const float* __restrict P, int n, float* __restrict vv, float* __restrict eh,
                      float* __restrict ev, float* __restrict ed) {
  for (int L = 0; L < n * n; ++L) {
    vv[L] = 0.625f * P[L] + 0.0625f * (((P[L + 1] + P[L - 1]) + (P[L + n] + P[L - n])) + (P[L + n - 1] + P[L - n + 1]));
    eh[L] = 0.375f * (P[L] + P[L + 1]) + 0.125f * (P[L + n] + P[L - n + 1]);
    ev[L] = 0.375f * (P[L] + P[L + n]) + 0.125f * (P[L + 1] + P[L + n - 1]);
    ed[L] = 0.375f * (P[L + 1] + P[L + n]) + 0.125f * (P[L] + P[L + n + 1]);
  }
}

// The limit position (class 0) and the two tangents (1, 2) at every square: Catmull-Clark's
// (16, 4, 1)/36 and Figure 21's stencils (T1 along a row, T2 across), or Loop's 1/2, 1/12 and its
// regular tangents, as catmark_limit_regular and loop_limit_regular compute them.
SDB_TILE_CLONES void quad_limit(const float* __restrict P, int n, float* __restrict pos, float* __restrict t1, float* __restrict t2) {
  for (int L = 0; L < n * n; ++L) {
    const float e0 = P[L + 1], e1 = P[L + n], e2 = P[L - 1], e3 = P[L - n];
    const float d0 = P[L + n + 1], d1 = P[L + n - 1], d2 = P[L - n - 1], d3 = P[L - n + 1];
    pos[L] = (1.0f / 36) * (16.0f * P[L] + 4.0f * ((e0 + e2) + (e1 + e3)) + ((d0 + d2) + (d1 + d3)));
    t1[L] = 4.0f * (e0 - e2) + ((d0 + d3) - (d1 + d2));
    t2[L] = 4.0f * (e1 - e3) + ((d0 + d1) - (d2 + d3));
  }
}
SDB_TILE_CLONES void triangle_limit(const float* __restrict P, int n, float* __restrict pos, float* __restrict t1,
                    float* __restrict t2) {
  for (int L = 0; L < n * n; ++L) {
    const float e0 = P[L + 1], e1 = P[L + n], e2 = P[L + n - 1], e3 = P[L - 1], e4 = P[L - n], e5 = P[L - n + 1];
    pos[L] = 0.5f * P[L] + (1.0f / 12) * (((e0 + e3) + (e1 + e4)) + (e2 + e5));
    t1[L] = (e0 - e3) + 0.5f * ((e1 - e2) - (e4 - e5));
    t2[L] = (e1 + e2) - (e4 + e5);
  }
}

// Unit T1 x T2 at every square.
SDB_TILE_CLONES void unit_normals(const float* __restrict ax, const float* __restrict ay, const float* __restrict az,
                                  const float* __restrict bx, const float* __restrict by, const float* __restrict bz,
                                  float* __restrict nx, float* __restrict ny, float* __restrict nz, int count) {
  for (int L = 0; L < count; ++L) {
    const float x = ay[L] * bz[L] - az[L] * by[L], y = az[L] * bx[L] - ax[L] * bz[L], z = ax[L] * by[L] - ay[L] * bx[L];
    const float l2 = x * x + y * y + z * z;
    const float inv = 1.0f / std::sqrt(l2 + 1e-37f);  // a zero normal stays zero; no branch, so SIMD lanes
    nx[L] = x * inv, ny[L] = y * inv, nz[L] = z * inv;
  }
}

}  // namespace sdb::mipgh::tile
