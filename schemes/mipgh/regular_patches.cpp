#include "schemes/mipgh/regular_patches.h"

#include <algorithm>
#include <cmath>

namespace sdb::mipgh {
namespace {

// The uniform cubic B-spline's four basis functions and their derivatives at t, in double.
void cubic_basis(double t, float* b, float* d) {
  const double s = 1 - t;
  b[0] = float(s * s * s / 6), b[1] = float((3 * t * t * t - 6 * t * t + 4) / 6);
  b[2] = float((-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6), b[3] = float(t * t * t / 6);
  d[0] = float(-s * s / 2), d[1] = float((3 * t * t - 4 * t) / 2), d[2] = float((-3 * t * t + 2 * t + 1) / 2),
  d[3] = float(t * t / 2);
}

// Corner k of a quad D-facet on its level-0 grid (row, column), and the grid directions of its
// outgoing side (A) and of its incoming side reversed (B): the ring's e[r] and e[r + 1].
constexpr int kCorner[4][2] = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
constexpr int kA[4][2] = {{0, 1}, {1, 0}, {0, -1}, {-1, 0}};
constexpr int kB[4][2] = {{1, 0}, {0, -1}, {-1, 0}, {0, 1}};

// The 16 vertices of regular D-facet f's net from its corners' rings; false where the rings do
// not close up into a 4 x 4 grid (or a vertex, edge or face around is not regular).
bool gather_net(const DAtlas& atlas, const EdgeTags& tags, int f, uint32_t* net) {
  if (atlas.facet_size[f] != 4) return false;
  int32_t grid[4][4];
  for (auto& row : grid)
    for (int32_t& g : row) g = -1;
  auto put = [&](int i, int j, int32_t v) {
    int32_t& g = grid[i + 1][j + 1];
    if (g >= 0 && g != v) return false;
    g = v;
    return true;
  };
  for (int k = 0; k < 4; ++k) {
    const int v = atlas.facet_corners[f][k];
    if (atlas.valence(v) != 4 || atlas.vertex_boundary[v] || atlas.vertex_fans[v] != 1) return false;
    const int begin = atlas.ring_offsets[v];
    int r = 0;
    while (r < 4 && atlas.ring[begin + r].facet != f) ++r;
    if (r == 4) return false;
    int32_t e[4], d[4];
    for (int i = 0; i < 4; ++i) {
      const HalfEdge& h = atlas.ring[begin + (r + i) % 4];
      if (atlas.facet_size[h.facet] != 4) return false;
      for (int s = 0; tags.any && s < 4; ++s)
        if (tags.slot[atlas.facet_edges[h.facet][s]] >= 0) return false;
      e[i] = atlas.facet_corners[h.facet][(h.side + 1) & 3], d[i] = atlas.facet_corners[h.facet][(h.side + 2) & 3];
    }
    const int pi = kCorner[k][0], pj = kCorner[k][1];
    auto at = [&](int a, int b, int32_t w) { return put(pi + a * kA[k][0] + b * kB[k][0], pj + a * kA[k][1] + b * kB[k][1], w); };
    if (!(at(0, 0, v) && at(1, 0, e[0]) && at(0, 1, e[1]) && at(-1, 0, e[2]) && at(0, -1, e[3]) && at(1, 1, d[0]) &&
          at(-1, 1, d[1]) && at(-1, -1, d[2]) && at(1, -1, d[3])))
      return false;
  }
  for (int i = 0; i < 16; ++i) {
    const int32_t w = grid[i / 4][i % 4];
    if (w < 0 || (tags.any && tags.vertex[0][w] != 0.0f)) return false;
    net[i] = uint32_t(w);
  }
  return true;
}

thread_local std::vector<V3> t_value, t_slope;  // per net row a and column: the patch along u, and d/du

}  // namespace

RegularPatches find_regular_patches(const DAtlas& atlas, const EdgeTags& tags, int depth) {
  RegularPatches p;
  p.patch.assign(atlas.num_facets(), -1);
  uint32_t net[16];
  for (int f = 0; f < atlas.num_facets(); ++f)
    if (gather_net(atlas, tags, f, net)) {
      p.patch[f] = int32_t(p.net.size() / 16);
      p.net.insert(p.net.end(), net, net + 16);
    }
  for (int sigma = 0; sigma <= depth; ++sigma) {
    const int n = (1 << sigma) + 1;
    std::vector<float> b(4 * size_t(n)), d(b.size());
    for (int k = 0; k < n; ++k) cubic_basis(double(k) / (n - 1), &b[4 * size_t(k)], &d[4 * size_t(k)]);
    p.basis.push_back(std::move(b)), p.derivative.push_back(std::move(d));
  }
  return p;
}

void RegularPatches::normals(int f, int sigma, const V3* base, int i0, int i1, int j0, int j1, int stride,
                             V3* out) const {
  const uint32_t* q = &net[size_t(patch[size_t(f)]) * 16];
  // The control points' differences from the facet's first corner (grid (0, 0)): exact to float's
  // relative precision however fine the level.
  V3 D[16];
  const V3 c = base[q[5]];
  for (int i = 0; i < 16; ++i) D[i] = base[q[i]] - c;
  const float *B = basis[size_t(sigma)].data(), *dB = derivative[size_t(sigma)].data();
  const int columns = j1 - j0 + 1;
  t_value.resize(4 * size_t(columns)), t_slope.resize(4 * size_t(columns));
  for (int a = 0; a < 4; ++a)
    for (int j = j0; j <= j1; ++j) {
      const float *b = B + 4 * j, *d = dB + 4 * j;
      const V3 *r = D + 4 * a;
      t_value[size_t(a * columns + j - j0)] = b[0] * r[0] + b[1] * r[1] + b[2] * r[2] + b[3] * r[3];
      t_slope[size_t(a * columns + j - j0)] = d[0] * r[0] + d[1] * r[1] + d[2] * r[2] + d[3] * r[3];
    }
  for (int i = i0; i <= i1; ++i) {
    const float *b = B + 4 * i, *d = dB + 4 * i;
    V3* row = out + size_t(i - i0) * size_t(stride);
    for (int j = 0; j < columns; ++j) {
      const V3 *value = t_value.data() + j, *slope = t_slope.data() + j;
      const V3 t1 = b[0] * slope[0] + b[1] * slope[columns] + b[2] * slope[2 * columns] + b[3] * slope[3 * columns];
      const V3 t2 = d[0] * value[0] + d[1] * value[columns] + d[2] * value[2 * columns] + d[3] * value[3 * columns];
      const V3 x = cross(t1, t2);
      const float inv = 1.0f / std::sqrt(x.x * x.x + x.y * x.y + x.z * x.z + 1e-37f);
      row[j] = inv * x;
    }
  }
}

std::vector<float> RegularPatches::node_weights(int sigma) {
  const int n = (1 << sigma) + 1;
  std::vector<float> w(size_t(n) * n * 32);
  std::vector<float> b(4 * size_t(n)), d(b.size());
  for (int k = 0; k < n; ++k) cubic_basis(double(k) / (n - 1), &b[4 * size_t(k)], &d[4 * size_t(k)]);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      float* at = &w[(size_t(i) * n + size_t(j)) * 32];
      for (int a = 0; a < 4; ++a)  // net row a (across, v), column c (along, u)
        for (int c = 0; c < 4; ++c) {
          at[4 * a + c] = float(double(b[4 * size_t(i) + a]) * d[4 * size_t(j) + c]);
          at[16 + 4 * a + c] = float(double(d[4 * size_t(i) + a]) * b[4 * size_t(j) + c]);
        }
    }
  return w;
}

void RegularPatches::side_normals(int f, int sigma, int side, const V3* base, V3* out) const {
  const int n = (1 << sigma) + 1;
  if (n < 3) return;
  // Side k's nodes a = 1 .. n - 2 run along one row or column (lod.h's side_ij), forwards or back.
  const RowColumn first = side_ij(4, side, n, 1, 0), last = side_ij(4, side, n, n - 2, 0);
  const int i0 = std::min(first.i, last.i), i1 = std::max(first.i, last.i);
  const int j0 = std::min(first.j, last.j), j1 = std::max(first.j, last.j);
  const bool backwards = first.i > last.i || first.j > last.j;
  thread_local std::vector<V3> t_line;
  t_line.resize(size_t(n));
  normals(f, sigma, base, i0, i1, j0, j1, i0 == i1 ? 0 : 1, t_line.data());
  for (int a = 0; a < n - 2; ++a) out[a] = t_line[size_t(backwards ? n - 3 - a : a)];
}

}  // namespace sdb::mipgh
