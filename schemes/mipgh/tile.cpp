#include "schemes/mipgh/tile.h"

#include <cmath>

namespace sdb::mipgh::tile {

// The tile's loops in AVX2 lanes where the CPU has them, SSE2 otherwise (as the fragments' kernel).
#define SDB_TILE_CLONES __attribute__((target_clones("avx2", "default")))

// Figure 20's stencils at every square of one coordinate's plane, rows w apart: vertex points
// (class 0), horizontal edge points (1), vertical ones (2), facet points (3).
SDB_TILE_CLONES void quad_classes(const float* __restrict P, int w, int count, float* __restrict vv, float* __restrict eh,
                                  float* __restrict ev, float* __restrict fv) {
  for (int L = 0; L < count; ++L) {
    vv[L] = 0.5625f * P[L] + 0.09375f * ((P[L + 1] + P[L - 1]) + (P[L + w] + P[L - w])) +
            0.015625f * ((P[L + w + 1] + P[L - w - 1]) + (P[L + w - 1] + P[L - w + 1]));
    eh[L] = 0.375f * (P[L] + P[L + 1]) + 0.0625f * ((P[L - w] + P[L - w + 1]) + (P[L + w] + P[L + w + 1]));
    ev[L] = 0.375f * (P[L] + P[L + w]) + 0.0625f * ((P[L - 1] + P[L + w - 1]) + (P[L + 1] + P[L + w + 1]));
    fv[L] = 0.25f * ((P[L] + P[L + w + 1]) + (P[L + 1] + P[L + w]));
  }
}

// Loop's, in triangles: vertex points (class 0), edge points of (a, b)-(a, b+1) (1),
// (a, b)-(a+1, b) (2) and the diagonal (a, b+1)-(a+1, b) (3).
SDB_TILE_CLONES void triangle_classes(const float* __restrict P, int w, int count, float* __restrict vv,
                                      float* __restrict eh, float* __restrict ev, float* __restrict ed) {
  for (int L = 0; L < count; ++L) {
    vv[L] = 0.625f * P[L] + 0.0625f * (((P[L + 1] + P[L - 1]) + (P[L + w] + P[L - w])) + (P[L + w - 1] + P[L - w + 1]));
    eh[L] = 0.375f * (P[L] + P[L + 1]) + 0.125f * (P[L + w] + P[L - w + 1]);
    ev[L] = 0.375f * (P[L] + P[L + w]) + 0.125f * (P[L + 1] + P[L + w - 1]);
    ed[L] = 0.375f * (P[L + 1] + P[L + w]) + 0.125f * (P[L] + P[L + w + 1]);
  }
}

// The limit position and the two tangents of one coordinate at square L: Catmull-Clark's
// (16, 4, 1)/36 and Figure 21's stencils (T1 along a row, T2 across), or Loop's 1/2, 1/12 and its
// regular tangents, as catmark_limit_regular and loop_limit_regular compute them.
struct LimitAt {
  float pos, t1, t2;
};
[[gnu::always_inline]] inline LimitAt quad_limit_at(const float* __restrict P, int w, int L) {
  const float e0 = P[L + 1], e1 = P[L + w], e2 = P[L - 1], e3 = P[L - w];
  const float d0 = P[L + w + 1], d1 = P[L + w - 1], d2 = P[L - w - 1], d3 = P[L - w + 1];
  return {(1.0f / 36) * (16.0f * P[L] + 4.0f * ((e0 + e2) + (e1 + e3)) + ((d0 + d2) + (d1 + d3))),
          4.0f * (e0 - e2) + ((d0 + d3) - (d1 + d2)), 4.0f * (e1 - e3) + ((d0 + d1) - (d2 + d3))};
}
[[gnu::always_inline]] inline LimitAt triangle_limit_at(const float* __restrict P, int w, int L) {
  const float e0 = P[L + 1], e1 = P[L + w], e2 = P[L + w - 1], e3 = P[L - 1], e4 = P[L - w], e5 = P[L - w + 1];
  return {0.5f * P[L] + (1.0f / 12) * (((e0 + e3) + (e1 + e4)) + (e2 + e5)), (e0 - e3) + 0.5f * ((e1 - e2) - (e4 - e5)),
          (e1 + e2) - (e4 + e5)};
}

// Unit T1 x T2; a zero normal stays zero, without a branch, so SIMD lanes.
[[gnu::always_inline]] inline void unit_cross(float ax, float ay, float az, float bx, float by, float bz, float& nx,
                                              float& ny, float& nz) {
  const float x = ay * bz - az * by, y = az * bx - ax * bz, z = ax * by - ay * bx;
  const float inv = 1.0f / std::sqrt(x * x + y * y + z * z + 1e-37f);
  nx = x * inv, ny = y * inv, nz = z * inv;
}

// Both in one loop over the three planes: the tangents stay in registers instead of going
// through planes of their own and a second loop.
template <class Stencil>
[[gnu::always_inline]] inline void limit_normals(Stencil at, const float* __restrict X, const float* __restrict Y,
                                                 const float* __restrict Z, int w, int count, float* __restrict px,
                                                 float* __restrict py, float* __restrict pz, float* __restrict nx,
                                                 float* __restrict ny, float* __restrict nz) {
#pragma GCC ivdep
  for (int L = 0; L < count; ++L) {
    const LimitAt x = at(X, w, L), y = at(Y, w, L), z = at(Z, w, L);
    px[L] = x.pos, py[L] = y.pos, pz[L] = z.pos;
    unit_cross(x.t1, y.t1, z.t1, x.t2, y.t2, z.t2, nx[L], ny[L], nz[L]);
  }
}

SDB_TILE_CLONES void quad_limit_normals(const float* __restrict X, const float* __restrict Y, const float* __restrict Z,
                                        int w, int count, float* __restrict px, float* __restrict py,
                                        float* __restrict pz, float* __restrict nx, float* __restrict ny,
                                        float* __restrict nz) {
  limit_normals(quad_limit_at, X, Y, Z, w, count, px, py, pz, nx, ny, nz);
}
SDB_TILE_CLONES void triangle_limit_normals(const float* __restrict X, const float* __restrict Y,
                                            const float* __restrict Z, int w, int count, float* __restrict px,
                                            float* __restrict py, float* __restrict pz, float* __restrict nx,
                                            float* __restrict ny, float* __restrict nz) {
  limit_normals(triangle_limit_at, X, Y, Z, w, count, px, py, pz, nx, ny, nz);
}

SDB_TILE_CLONES void quad_limit_positions(const float* __restrict X, const float* __restrict Y,
                                          const float* __restrict Z, int w, int count, float* __restrict px,
                                          float* __restrict py, float* __restrict pz) {
  for (int L = 0; L < count; ++L) px[L] = quad_limit_at(X, w, L).pos, py[L] = quad_limit_at(Y, w, L).pos, pz[L] = quad_limit_at(Z, w, L).pos;
}

namespace {

// A cubic's value and slope at `count` points from its four coefficients r: v = sum_m B_m r_m,
// s = sum_m B'_m r_m, B_m at f[m * n + k] and B'_m at f[(4 + m) * n + k] for point k.
[[gnu::always_inline]] inline void cubic_row(const float* __restrict f, int n, float r0, float r1, float r2, float r3,
                                             int count, float* __restrict v, float* __restrict s) {
  const float *__restrict b0 = f, *__restrict b1 = f + n, *__restrict b2 = f + 2 * n, *__restrict b3 = f + 3 * n;
  const float *__restrict d0 = f + 4 * n, *__restrict d1 = f + 5 * n, *__restrict d2 = f + 6 * n, *__restrict d3 = f + 7 * n;
  for (int k = 0; k < count; ++k) {
    v[k] = (b0[k] * r0 + b1[k] * r1) + (b2[k] * r2 + b3[k] * r3);
    s[k] = (d0[k] * r0 + d1[k] * r1) + (d2[k] * r2 + d3[k] * r3);
  }
}

// Limit positions and unit normals (T1 x T2) of `count` nodes from sums over four rows: the
// position corner + sum_a b[a] value_a, T1 = sum_a b[a] slope_a, T2 = sum_a d[a] value_a, per
// coordinate k the rows value[a][k], slope[a][k].
[[gnu::always_inline]] inline void sum_limit(const float* const (&value)[4][3], const float* const (&slope)[4][3],
                                             const float* b, const float* d, V3 corner, int count,
                                             float* __restrict px, float* __restrict py, float* __restrict pz,
                                             float* __restrict nx, float* __restrict ny, float* __restrict nz) {
  const float b0 = b[0], b1 = b[1], b2 = b[2], b3 = b[3], d0 = d[0], d1 = d[1], d2 = d[2], d3 = d[3];
  const float *__restrict sx0 = slope[0][0], *__restrict sx1 = slope[1][0], *__restrict sx2 = slope[2][0], *__restrict sx3 = slope[3][0];
  const float *__restrict sy0 = slope[0][1], *__restrict sy1 = slope[1][1], *__restrict sy2 = slope[2][1], *__restrict sy3 = slope[3][1];
  const float *__restrict sz0 = slope[0][2], *__restrict sz1 = slope[1][2], *__restrict sz2 = slope[2][2], *__restrict sz3 = slope[3][2];
  const float *__restrict vx0 = value[0][0], *__restrict vx1 = value[1][0], *__restrict vx2 = value[2][0], *__restrict vx3 = value[3][0];
  const float *__restrict vy0 = value[0][1], *__restrict vy1 = value[1][1], *__restrict vy2 = value[2][1], *__restrict vy3 = value[3][1];
  const float *__restrict vz0 = value[0][2], *__restrict vz1 = value[1][2], *__restrict vz2 = value[2][2], *__restrict vz3 = value[3][2];
#pragma GCC ivdep
  for (int j = 0; j < count; ++j) {
    px[j] = corner.x + ((b0 * vx0[j] + b1 * vx1[j]) + (b2 * vx2[j] + b3 * vx3[j]));
    py[j] = corner.y + ((b0 * vy0[j] + b1 * vy1[j]) + (b2 * vy2[j] + b3 * vy3[j]));
    pz[j] = corner.z + ((b0 * vz0[j] + b1 * vz1[j]) + (b2 * vz2[j] + b3 * vz3[j]));
    const float ax = (b0 * sx0[j] + b1 * sx1[j]) + (b2 * sx2[j] + b3 * sx3[j]);
    const float ay = (b0 * sy0[j] + b1 * sy1[j]) + (b2 * sy2[j] + b3 * sy3[j]);
    const float az = (b0 * sz0[j] + b1 * sz1[j]) + (b2 * sz2[j] + b3 * sz3[j]);
    const float cx = (d0 * vx0[j] + d1 * vx1[j]) + (d2 * vx2[j] + d3 * vx3[j]);
    const float cy = (d0 * vy0[j] + d1 * vy1[j]) + (d2 * vy2[j] + d3 * vy3[j]);
    const float cz = (d0 * vz0[j] + d1 * vz1[j]) + (d2 * vz2[j] + d3 * vz3[j]);
    unit_cross(ax, ay, az, cx, cy, cz, nx[j], ny[j], nz[j]);
  }
}

}  // namespace

SDB_TILE_CLONES void patch_limit(const float* f, int n, const V3 (&net)[16], V3 corner, const float* b,
                                     const float* d, int rows, int columns, int stride, float* scratch, float* px,
                                     float* py, float* pz, float* nx, float* ny, float* nz) {
  const float* value[4][3];
  const float* slope[4][3];
  for (int a = 0; a < 4; ++a) {
    const V3 *r = &net[4 * a];
    float* v = scratch + size_t(a * 6) * size_t(columns);
    cubic_row(f, n, r[0].x, r[1].x, r[2].x, r[3].x, columns, v, v + columns);
    cubic_row(f, n, r[0].y, r[1].y, r[2].y, r[3].y, columns, v + 2 * columns, v + 3 * columns);
    cubic_row(f, n, r[0].z, r[1].z, r[2].z, r[3].z, columns, v + 4 * columns, v + 5 * columns);
    for (int k = 0; k < 3; ++k) value[a][k] = v + 2 * k * columns, slope[a][k] = v + (2 * k + 1) * columns;
  }
  for (int i = 1; i <= rows; ++i) {
    const size_t at = size_t(i - 1) * size_t(stride);
    sum_limit(value, slope, b + 4 * i, d + 4 * i, corner, columns, px + at, py + at, pz + at, nx + at, ny + at, nz + at);
  }
}

// Eight nodes' sums in one vector each (GCC's generic vectors: one AVX register, or two SSE ones),
// spelled out: left to itself the compiler vectorises across the terms instead.
using F8 = float __attribute__((vector_size(32)));

SDB_TILE_CLONES void weighted_normals(const float* __restrict w, size_t pitch, const V3* __restrict p, int terms,
                                      int count, V3* __restrict out) {
  constexpr int kLanes = 8;
  for (int first = 0; first < count; first += kLanes) {
    F8 ax{}, ay{}, az{}, bx{}, by{}, bz{};
    for (int c = 0; c < terms; ++c) {
      const float* u = w + 2 * size_t(c) * pitch + size_t(first);
      F8 s, t;
      __builtin_memcpy(&s, u, sizeof s), __builtin_memcpy(&t, u + pitch, sizeof t);
      const float x = p[c].x, y = p[c].y, z = p[c].z;
      ax += s * x, ay += s * y, az += s * z;
      bx += t * x, by += t * y, bz += t * z;
    }
    float nx[kLanes], ny[kLanes], nz[kLanes];
    for (int l = 0; l < kLanes; ++l) unit_cross(ax[l], ay[l], az[l], bx[l], by[l], bz[l], nx[l], ny[l], nz[l]);
    const int lanes = count - first < kLanes ? count - first : kLanes;
    for (int l = 0; l < lanes; ++l) out[first + l] = {nx[l], ny[l], nz[l]};
  }
}

SDB_TILE_CLONES void line_limit(const float* __restrict f, int n, const V3 (&along)[4], const V3 (&across)[4],
                                V3 corner, int count, float* __restrict px, float* __restrict py,
                                float* __restrict pz, float* __restrict nx, float* __restrict ny,
                                float* __restrict nz) {
  const float *__restrict b0 = f, *__restrict b1 = f + n, *__restrict b2 = f + 2 * n, *__restrict b3 = f + 3 * n;
  const float *__restrict d0 = f + 4 * n, *__restrict d1 = f + 5 * n, *__restrict d2 = f + 6 * n, *__restrict d3 = f + 7 * n;
  const V3 P0 = along[0], P1 = along[1], P2 = along[2], P3 = along[3];
  const V3 Q0 = across[0], Q1 = across[1], Q2 = across[2], Q3 = across[3];
#pragma GCC ivdep
  for (int k = 0; k < count; ++k) {
    px[k] = corner.x + ((b0[k] * P0.x + b1[k] * P1.x) + (b2[k] * P2.x + b3[k] * P3.x));
    py[k] = corner.y + ((b0[k] * P0.y + b1[k] * P1.y) + (b2[k] * P2.y + b3[k] * P3.y));
    pz[k] = corner.z + ((b0[k] * P0.z + b1[k] * P1.z) + (b2[k] * P2.z + b3[k] * P3.z));
    const float ax = (d0[k] * P0.x + d1[k] * P1.x) + (d2[k] * P2.x + d3[k] * P3.x);
    const float ay = (d0[k] * P0.y + d1[k] * P1.y) + (d2[k] * P2.y + d3[k] * P3.y);
    const float az = (d0[k] * P0.z + d1[k] * P1.z) + (d2[k] * P2.z + d3[k] * P3.z);
    const float cx = (b0[k] * Q0.x + b1[k] * Q1.x) + (b2[k] * Q2.x + b3[k] * Q3.x);
    const float cy = (b0[k] * Q0.y + b1[k] * Q1.y) + (b2[k] * Q2.y + b3[k] * Q3.y);
    const float cz = (b0[k] * Q0.z + b1[k] * Q1.z) + (b2[k] * Q2.z + b3[k] * Q3.z);
    unit_cross(ax, ay, az, cx, cy, cz, nx[k], ny[k], nz[k]);
  }
}

namespace {

// Four nodes at a time between the level's packed V3s and the tile's planes: three 16-byte loads
// or stores and five or six in-register shuffles (SSE, the x86-64 baseline) instead of twelve
// scalar moves. Rows here are 1 to 15 nodes long, so four lanes leave less to the scalar tails
// than eight would. Pure copies and the same additions: the bits do not change.
static_assert(sizeof(V3) == 3 * sizeof(float), "V3 is three packed floats");
using F4 = float __attribute__((vector_size(16)));
#define SDB_TILE_INLINE [[gnu::always_inline]] inline

SDB_TILE_INLINE F4 load4(const float* p) {
  F4 v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
SDB_TILE_INLINE void store4(float* p, F4 v) { __builtin_memcpy(p, &v, sizeof v); }
SDB_TILE_INLINE F4 reversed(F4 v) { return __builtin_shufflevector(v, v, 3, 2, 1, 0); }

struct Xyz4 {
  F4 x, y, z;
};
// p[0..3] as three coordinate vectors.
SDB_TILE_INLINE Xyz4 deinterleave(const V3* p) {
  const float* f = &p->x;
  const F4 m0 = load4(f), m1 = load4(f + 4), m2 = load4(f + 8);  // x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3
  const F4 xy = __builtin_shufflevector(m1, m2, 2, 3, 5, 6);      // x2 y2 x3 y3
  const F4 yz = __builtin_shufflevector(m0, m1, 1, 2, 4, 5);      // y0 z0 y1 z1
  return {__builtin_shufflevector(m0, xy, 0, 3, 4, 6), __builtin_shufflevector(yz, xy, 0, 2, 5, 7),
          __builtin_shufflevector(yz, m2, 1, 3, 4, 7)};
}
// The inverse: four nodes' coordinates into p[0..3].
SDB_TILE_INLINE void interleave(F4 x, F4 y, F4 z, V3* p) {
  float* f = &p->x;
  const F4 xy = __builtin_shufflevector(x, y, 0, 2, 4, 6);  // x0 x2 y0 y2
  const F4 yz = __builtin_shufflevector(y, z, 1, 3, 5, 7);  // y1 y3 z1 z3
  const F4 zx = __builtin_shufflevector(z, x, 0, 2, 5, 7);  // z0 z2 x1 x3
  store4(f, __builtin_shufflevector(xy, zx, 0, 2, 4, 6));
  store4(f + 4, __builtin_shufflevector(yz, xy, 0, 2, 5, 7));
  store4(f + 8, __builtin_shufflevector(zx, yz, 1, 3, 5, 7));
}

// Nodes 1 .. length - 2 of a row into the planes, node k at x[k * kStep], from a run in storage:
// node k at run[k - 1], or (descending) at run[-(k - 1)].
template <int kStep>
SDB_TILE_INLINE void load_run(const V3* __restrict run, bool descending, int length, float* __restrict x,
                              float* __restrict y, float* __restrict z) {
  const bool flip = (kStep < 0) != descending;
  int k = 1;
  for (; k + 4 < length; k += 4) {  // nodes k .. k + 3, stored at k or (turned) at -(k + 3)
    const Xyz4 v = deinterleave(descending ? run - (k + 2) : run + (k - 1));
    const int at = kStep > 0 ? k : -(k + 3);
    store4(x + at, flip ? reversed(v.x) : v.x);
    store4(y + at, flip ? reversed(v.y) : v.y);
    store4(z + at, flip ? reversed(v.z) : v.z);
  }
  for (; k + 1 < length; ++k) {
    const V3& p = run[descending ? -(k - 1) : k - 1];
    x[k * kStep] = p.x, y[k * kStep] = p.y, z[k * kStep] = p.z;
  }
}

// One row of a D-facet's nodes into the planes, node k at x[k * kStep], the two ends through the
// index array: where `inner`, the others from `inside`, the interior's next nodes in storage (the
// pointer moves past them); else the row lies along a side, whose inner nodes are its D-edge's,
// a run in storage either way (lod.h).
template <int kStep>
SDB_TILE_INLINE void load_row(const uint32_t* __restrict idx, int length, bool inner, const V3* __restrict& inside,
                              const V3* __restrict src, float* __restrict x, float* __restrict y,
                              float* __restrict z) {
  auto put = [&](int k, const V3& p) { x[k * kStep] = p.x, y[k * kStep] = p.y, z[k * kStep] = p.z; };
  put(0, src[idx[0]]);
  if (length == 1) return;
  put(length - 1, src[idx[length - 1]]);
  if (inner) {
    load_run<kStep>(inside, false, length, x, y, z);
    inside += length - 2;
    return;
  }
  if (length < 3) return;
  const uint32_t first = idx[1], last = idx[length - 2];
  if (last - first == uint32_t(length - 3)) load_run<kStep>(src + first, false, length, x, y, z);
  else if (first - last == uint32_t(length - 3)) load_run<kStep>(src + first, true, length, x, y, z);
  else
    for (int k = 1; k + 1 < length; ++k) put(k, src[idx[k]]);
}

// Here and in the assembly below, no auto-vectorization: the scalar tails are at most three
// nodes, and vectorized, their alias checks and set-up cost more than the moves.
template <int kStep>
[[gnu::optimize("no-tree-vectorize")]] void load_triangle_rows(const uint32_t* idx, const V3* inside, int n, const V3* src, float* x, float* y, float* z) {
  const int w = n + 1;
  for (int i = 0; i < n; idx += n - i, ++i) {
    // node (i, j) at i w + j, or turned at (n - 1 - i) w + n - j
    const int row = kStep > 0 ? i * w : (n - 1 - i) * w + n;
    load_row<kStep>(idx, n - i, i > 0, inside, src, x + row, y + row, z + row);
  }
}

}  // namespace

void Tile::load_quad(const uint32_t* idx, const V3* inside, int n, const V3* src) {
  shape(n, n);
  float *x = plane(0), *y = plane(1), *z = plane(2);
  // Short rows: through the index array, node by node, with no per-row set-up; long ones copy
  // their interior.
  if (n < kLongRow) {
    for (int i = 0; i < n * n; ++i) {
      const V3& p = src[idx[i]];
      x[i] = p.x, y[i] = p.y, z[i] = p.z;
    }
    return;
  }
  for (int i = 0; i < n; ++i, idx += n) load_row<1>(idx, n, i > 0 && i + 1 < n, inside, src, x + i * n, y + i * n, z + i * n);
}

void split_run(const V3* p, int count, float* x, float* y, float* z) {
  // load_run's nodes 1 .. count of a row count + 2 long, node k at x[k - 1]
  load_run<1>(p, false, count + 2, x - 1, y - 1, z - 1);
}

void Tile::load_triangle(const uint32_t* idx, const V3* inside, int n, const V3* src, bool turned) {
  shape(n, n + 1);
  if (turned) load_triangle_rows<-1>(idx, inside, n, src, plane(0), plane(1), plane(2));
  else load_triangle_rows<1>(idx, inside, n, src, plane(0), plane(1), plane(2));
}

namespace {

template <bool kTurned>
[[gnu::optimize("no-tree-vectorize")]] void assemble_targets_rows(const Planes& s, int n, int w, int width, bool quad,
                                                                 V3* __restrict out) {
  for (int r = 1; r <= width; ++r) {
    // odd columns from class a, even ones from b: columns 2k + 1, 2k + 2 at squares k, k + 1, or
    // turned, both at n - (k + 1)
    const int odd = (r & 1) << 1, row = (kTurned ? n - 1 - ((r + 1) >> 1) : r >> 1) * w + (kTurned ? n : 0);
    const int end = quad ? width : width - r;
    const float *__restrict ax = s.v[odd | 1][0].data() + row, *__restrict ay = s.v[odd | 1][1].data() + row,
                            *__restrict az = s.v[odd | 1][2].data() + row;
    const float *__restrict bx = s.v[odd][0].data() + row, *__restrict by = s.v[odd][1].data() + row,
                            *__restrict bz = s.v[odd][2].data() + row;
    int c = 1;
    // columns c .. c + 7: a at squares k .. k + 3 and b at k + 1 .. k + 4, alternating; turned,
    // both at -(k + 1) down to -(k + 4)
    for (; c + 7 <= end; c += 8, out += 8) {
      const int k = c >> 1, La = kTurned ? -(k + 4) : k, Lb = kTurned ? -(k + 4) : k + 1;
      auto pair = [&](const float* a, const float* b, F4& lo, F4& hi) {
        const F4 u = load4(a + La), v = load4(b + Lb);
        lo = kTurned ? __builtin_shufflevector(u, v, 3, 7, 2, 6) : __builtin_shufflevector(u, v, 0, 4, 1, 5);
        hi = kTurned ? __builtin_shufflevector(u, v, 1, 5, 0, 4) : __builtin_shufflevector(u, v, 2, 6, 3, 7);
      };
      F4 x0, x1, y0, y1, z0, z1;
      pair(ax, bx, x0, x1), pair(ay, by, y0, y1), pair(az, bz, z0, z1);
      interleave(x0, y0, z0, out);
      interleave(x1, y1, z1, out + 4);
    }
    for (; c < end; c += 2, out += 2) {
      const int k = c >> 1, La = kTurned ? -(k + 1) : k, Lb = kTurned ? -(k + 1) : k + 1;
      out[0] = {ax[La], ay[La], az[La]};
      out[1] = {bx[Lb], by[Lb], bz[Lb]};
    }
    if (c == end) {
      const int k = c >> 1, La = kTurned ? -(k + 1) : k;
      *out++ = {ax[La], ay[La], az[La]};
    }
  }
}

template <bool kTurned, bool kOffset>
[[gnu::optimize("no-tree-vectorize")]] void assemble_limit_rows(const Planes& s, int n, int w, int inner, bool quad,
                                                               const V3& o, V3* __restrict p, V3* __restrict q) {
  const float *__restrict px = s.v[0][0].data(), *__restrict py = s.v[0][1].data(), *__restrict pz = s.v[0][2].data();
  const float *__restrict nx = s.normal[0].data(), *__restrict ny = s.normal[1].data(),
                          *__restrict nz = s.normal[2].data();
  const F4 ox = F4{} + o.x, oy = F4{} + o.y, oz = F4{} + o.z;
  for (int i = 1; i <= inner; ++i) {
    // node (i, j) at square i w + j, or turned at (n - 1 - i) w + n - j
    const int row = kTurned ? (n - 1 - i) * w + n : i * w, count = quad ? inner : inner - i;
    int j = 1;
    for (; j + 3 <= count; j += 4, p += 4, q += 4) {  // nodes j .. j + 3
      const int L = kTurned ? row - j - 3 : row + j;
      auto at = [&](const float* plane) { return kTurned ? reversed(load4(plane + L)) : load4(plane + L); };
      if (kOffset) interleave(at(px) + ox, at(py) + oy, at(pz) + oz, p);
      else interleave(at(px), at(py), at(pz), p);
      interleave(at(nx), at(ny), at(nz), q);
    }
    for (; j <= count; ++j, ++p, ++q) {
      const int L = kTurned ? row - j : row + j;
      *p = kOffset ? V3{px[L] + o.x, py[L] + o.y, pz[L] + o.z} : V3{px[L], py[L], pz[L]};
      *q = {nx[L], ny[L], nz[L]};
    }
  }
}

template <bool kOffset>
[[gnu::optimize("no-tree-vectorize")]] void assemble_limit_nodes(const Planes& s, int count, const V3& o,
                                                                V3* __restrict p, V3* __restrict q) {
  const float *__restrict px = s.v[0][0].data(), *__restrict py = s.v[0][1].data(), *__restrict pz = s.v[0][2].data();
  const float *__restrict nx = s.normal[0].data(), *__restrict ny = s.normal[1].data(),
                          *__restrict nz = s.normal[2].data();
  const F4 ox = F4{} + o.x, oy = F4{} + o.y, oz = F4{} + o.z;
  int L = 0;
  for (; L + 4 <= count; L += 4, p += 4, q += 4) {
    if (kOffset) interleave(load4(px + L) + ox, load4(py + L) + oy, load4(pz + L) + oz, p);
    else interleave(load4(px + L), load4(py + L), load4(pz + L), p);
    interleave(load4(nx + L), load4(ny + L), load4(nz + L), q);
  }
  for (; L < count; ++L, ++p, ++q) {
    *p = kOffset ? V3{px[L] + o.x, py[L] + o.y, pz[L] + o.z} : V3{px[L], py[L], pz[L]};
    *q = {nx[L], ny[L], nz[L]};
  }
}

}  // namespace

void assemble_targets(const Planes& s, int n, int stride, int width, bool quad, bool turned, V3* out) {
  if (turned) assemble_targets_rows<true>(s, n, stride, width, quad, out);
  else assemble_targets_rows<false>(s, n, stride, width, quad, out);
}

void assemble_limit(const Planes& s, int n, int stride, int inner, bool quad, bool turned, const V3* offset,
                    V3* position, V3* normal) {
  const V3 o = offset ? *offset : V3{0, 0, 0};
  if (turned) {
    if (offset) assemble_limit_rows<true, true>(s, n, stride, inner, quad, o, position, normal);
    else assemble_limit_rows<true, false>(s, n, stride, inner, quad, o, position, normal);
  } else {
    if (offset) assemble_limit_rows<false, true>(s, n, stride, inner, quad, o, position, normal);
    else assemble_limit_rows<false, false>(s, n, stride, inner, quad, o, position, normal);
  }
}

void assemble_limit_run(const Planes& s, int count, const V3* offset, V3* position, V3* normal) {
  if (offset) assemble_limit_nodes<true>(s, count, *offset, position, normal);
  else assemble_limit_nodes<false>(s, count, V3{0, 0, 0}, position, normal);
}

}  // namespace sdb::mipgh::tile
