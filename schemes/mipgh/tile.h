// The D-facet visits' tile (processor.cpp): a facet's nodes of one level in three float planes,
// and the stencils that run over its whole square in SIMD lanes. Plain loops over floats; the
// processor gathers the tile and assembles the targets.
#pragma once

#include <cstdint>
#include <vector>

#include "schemes/mipgh/shader.h"

namespace sdb::mipgh::tile {

// A D-facet's nodes of one level, gathered once through its index array into three planes (the
// work-group tile a GPU would stage in shared memory), `rows` rows `stride` floats apart, with
// stride + 1 floats of padding on either side: the stencils then run over the whole tile as one
// long SIMD loop with fixed neighbour offsets (+-1 along a row, +-stride across), and the values
// at squares no target uses are dropped.
//   - A quad: its n x n array as it is (stride n).
//   - Triangles, two to a tile (load_triangle): the first's node (i, j) at i (n + 1) + j, the
//     lower-left half of an n x (n + 1) rectangle; the second turned half a turn into the other
//     half, its (i, j) at (n - 1 - i)(n + 1) + n - j. Alone, a triangle would leave half of an
//     n x n square to waste. Loop's stencils are symmetric under the turn, to the bit (each sum
//     adds the same pairs, swapped): the second triangle's targets are its own, at the turned
//     squares (target (R, C) of the doubled grid at (2n - 2 - R, 2n - C)), and its tangents
//     change sign both, so its normals do not (but for the sign of a zero component: a - a is
//     +0 either way round).
//   - A strip (load_strip_rows in processor.cpp): three rows of a D-edge's nodes.
// Nodes along a side from which a row is long enough for per-row work (a triangle tile's or a
// quad's interior copied row by row, a D-edge strip run through the SIMD stencils) to pay for its
// set-up: N = 17, the last level of depth 4. Below, node-by-node loops (callgrind: the per-row set-up
// cost +19% to +27% instructions on small meshes at N <= 9).
constexpr int kLongRow = 17;

struct Tile {
  std::vector<float> storage[3];
  int rows = 0, stride = 0;
  float* plane(int k) { return storage[k].data() + stride + 1; }
  const float* plane(int k) const { return storage[k].data() + stride + 1; }
  int squares() const { return rows * stride; }
  // Room for rows x stride; the floats a previous shape left are kept (finite, and read only for
  // targets that are dropped).
  void shape(int r, int w) {
    rows = r, stride = w;
    const size_t wanted = size_t(r) * w + 2 * size_t(w + 1);
    for (auto& s : storage)
      if (s.size() < wanted) s.resize(wanted, 0.0f);
  }
  // A D-facet's nodes: `idx` its index array, `inside` its interior nodes (row-major, contiguous
  // in the level's storage: a triangle's, and a quad's from kLongRow on, copied row by row rather
  // than gathered node by node).
  void load_quad(const uint32_t* idx, const V3* inside, int n, const V3* src);
  // One triangle, or (turned) the second of two.
  void load_triangle(const uint32_t* idx, const V3* inside, int n, const V3* src, bool turned);
};

// `count` consecutive nodes from p into three planes (a D-edge's nodes, which lie together in
// the level's storage).
void split_run(const V3* p, int count, float* x, float* y, float* z);

// The stencils' results over a tile's square: four classes of target per source square L = (a, b)
// (the target at (2a + r, 2b + c) for class 2r + c), or the limit position (class 0) and `normal`.
struct Planes {
  std::vector<float> v[4][3], normal[3];
  size_t size = 0;
  void fit(size_t wanted) {  // grows only
    if (wanted <= size) return;
    size = wanted;
    for (auto& c : v)
      for (auto& p : c) p.resize(size);
    for (auto& p : normal) p.resize(size);
  }
};

// Each runs over squares 0 .. count - 1 of one coordinate's plane P, rows `stride` apart (a Tile's
// plane, padded).
// Figure 20's stencils: vertex points (class 0), horizontal edge points (1), vertical ones (2),
// facet points (3).
void quad_classes(const float* P, int stride, int count, float* vv, float* eh, float* ev, float* fv);
// Loop's, in triangles: vertex points (0), edge points of (a, b)-(a, b+1) (1), (a, b)-(a+1, b) (2)
// and the diagonal (a, b+1)-(a+1, b) (3).
void triangle_classes(const float* P, int stride, int count, float* vv, float* eh, float* ev, float* ed);
// The limit positions and unit normals (T1 x T2 of the regular tangents, as
// catmark_limit_regular and loop_limit_regular compute them) over squares 0 .. count - 1 of the
// three planes X, Y, Z.
void quad_limit_normals(const float* X, const float* Y, const float* Z, int stride, int count, float* px, float* py,
                        float* pz, float* nx, float* ny, float* nz);
void triangle_limit_normals(const float* X, const float* Y, const float* Z, int stride, int count, float* px, float* py,
                            float* pz, float* nx, float* ny, float* nz);
// The limit positions alone (a quad whose normals come from level 0: regular_patches.h).
void quad_limit_positions(const float* X, const float* Y, const float* Z, int stride, int count, float* px, float* py,
                          float* pz);
// Limit positions and unit normals (T1 x T2, u along a row) of a bicubic patch at the grid nodes
// (i, j), i = 1 .. rows, j = 1 .. columns, into three planes each at (i - 1) stride + j - 1 (rows
// written in order, so a row of `columns` > stride ends under the next one's start): its 16
// control points `net` as differences from `corner` (row-major, net row a at 4 a), the basis at the
// columns from f (B_m(j) at f[m * n + j - 1], B'_m at f[(4 + m) * n + j - 1]) and at the rows from
// b and d (B_m(i) at b[4 i + m], B'_m at d[4 i + m]). Per net row and coordinate, the patch along
// u and its slope first (24 rows of `columns` in `scratch`), then three four-term sums per node.
void patch_limit(const float* f, int n, const V3 (&net)[16], V3 corner, const float* b, const float* d, int rows,
                 int columns, int stride, float* scratch, float* px, float* py, float* pz, float* nx, float* ny,
                 float* nz);
// Unit normals (T1 x T2) of `count` nodes whose tangents are weighted sums of `terms` points p:
// T1 = sum_c w[2 c pitch + node] p[c], T2 = sum_c w[(2 c + 1) pitch + node] p[c] (weights by point,
// nodes contiguous: eight nodes' sums per SIMD lane; rows readable 8 floats past `count`).
void weighted_normals(const float* w, size_t pitch, const V3* p, int terms, int count, V3* out);
// Positions corner + C(t_k) and unit normals (C' x X) at `count` points t_k of one line of a
// bicubic patch: C(t) = sum_m B_m(t) along[m] the patch along it, X(t) = sum_m B_m(t) across[m]
// its derivative across; B_m(t_k) at f[m * n + k] and B'_m(t_k) at f[(4 + m) * n + k]
// (patch_limit's table).
void line_limit(const float* f, int n, const V3 (&along)[4], const V3 (&across)[4], V3 corner, int count, float* px,
                float* py, float* pz, float* nx, float* ny, float* nz);
// A step's targets in one D-facet of the tile whose class planes `s` holds (a quad, the first
// triangle, or the turned one): level sigma + 1's interior rows 1 .. width, row-major into `out`.
// Target (r, c) lies at square (r >> 1, c >> 1), class 2 (r & 1) + (c & 1), or at the turned
// square (Tile); n the tile's nodes along a side, `stride` its rows' distance.
void assemble_targets(const Planes& s, int n, int stride, int width, bool quad, bool turned, V3* out);
// A projection's: the interior nodes' limit positions (class 0, moved by *offset where given) and
// normals, rows 1 .. inner.
void assemble_limit(const Planes& s, int n, int stride, int inner, bool quad, bool turned, const V3* offset,
                    V3* position, V3* normal);
// The same from planes that hold `count` nodes one after another (patch_limit's at stride n - 2:
// a quad's whole interior as one run, four nodes to a move, where rows of n - 2 left a scalar
// tail each).
void assemble_limit_run(const Planes& s, int count, const V3* offset, V3* position, V3* normal);

}  // namespace sdb::mipgh::tile
