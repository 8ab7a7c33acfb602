#include "schemes/mipgh/regular_patches.h"

#include "schemes/mipgh/tile.h"

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
    std::vector<float> f(8 * size_t(n));
    for (int k = 0; k < n; ++k)
      for (int m = 0; m < 4; ++m) f[size_t(m * n + k)] = b[4 * size_t(k) + m], f[size_t((4 + m) * n + k)] = d[4 * size_t(k) + m];
    p.basis.push_back(std::move(b)), p.derivative.push_back(std::move(d)), p.by_function.push_back(std::move(f));
  }
  return p;
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

void RegularPatches::interior_limit(int f, int sigma, const V3* base, V3 origin, float* px, float* py, float* pz,
                                    float* nx, float* ny, float* nz) const {
  const uint32_t* q = &net[size_t(patch[size_t(f)]) * 16];
  const V3 c = base[q[5]];
  V3 D[16];
  for (int i = 0; i < 16; ++i) D[i] = base[q[i]] - c;
  // Columns 1 .. n - 2 rounded up to whole SIMD vectors of eight up to column n - 1 (the side's,
  // written where the next row then starts, or one past the last row): at n = 17, 15 columns
  // left seven to a scalar tail.
  const int n = (1 << sigma) + 1, columns = std::min(((n - 2) + 7) & ~7, n - 1);
  thread_local std::vector<float> t_rows;
  t_rows.resize(24 * size_t(columns));
  tile::patch_limit(by_function[size_t(sigma)].data() + 1, n, D, c - origin, basis[size_t(sigma)].data(),
                    derivative[size_t(sigma)].data(), n - 2, columns, n - 2, t_rows.data(), px, py, pz, nx, ny, nz);
}

void RegularPatches::side_limit(int f, int sigma, int side, const V3* base, V3 origin, const V3* offset, V3* position,
                                V3* normal) const {
  const int n = (1 << sigma) + 1, count = n - 2;
  if (count < 1) return;
  // Side k's nodes run along one row (sides 0, 2) or column (1, 3) of the grid (lod.h's side_ij),
  // forwards (0, 1) or backwards. The net reduced once to that line (four points for the patch
  // along it, four for its derivative across), then three four-term sums per node; along a
  // column u and v trade places (T2 x T1: the normal turned round).
  const bool row = side == 0 || side == 2, backwards = side >= 2;
  const uint32_t* q = &net[size_t(patch[size_t(f)]) * 16];
  const V3 c = base[q[5]];
  const int fixed = side == 0 || side == 3 ? 0 : n - 1;
  const float *b = basis[size_t(sigma)].data() + 4 * fixed, *d = derivative[size_t(sigma)].data() + 4 * fixed;
  V3 along[4], across[4];
  for (int k = 0; k < 4; ++k) {  // line k: net column k across the rows (a row side), or net row k
    V3 p[4];
    for (int m = 0; m < 4; ++m) p[m] = base[q[row ? 4 * m + k : 4 * k + m]] - c;
    along[k] = (b[0] * p[0] + b[1] * p[1]) + (b[2] * p[2] + b[3] * p[3]);
    across[k] = (d[0] * p[0] + d[1] * p[1]) + (d[2] * p[2] + d[3] * p[3]);
  }
  // Points 1 .. n - 2, rounded up to whole SIMD vectors where the table has room (as interior_planes).
  const int points = std::min((count + 7) & ~7, n - 1);
  constexpr int kOnStack = 32;
  float stack[6 * kOnStack];
  thread_local std::vector<float> t_planes;
  if (points > kOnStack) t_planes.resize(6 * size_t(points));
  float* px = points > kOnStack ? t_planes.data() : stack;
  float *py = px + points, *pz = py + points, *nx = pz + points, *ny = nx + points, *nz = ny + points;
  tile::line_limit(by_function[size_t(sigma)].data() + 1, n, along, across, c - origin, points, px, py, pz, nx, ny, nz);
  const float sign = row ? 1.0f : -1.0f;
  const V3 o = offset ? *offset : V3{0, 0, 0};
  for (int a = 0; a < count; ++a) {
    const int t = backwards ? count - 1 - a : a;
    position[a] = offset ? V3{px[t] + o.x, py[t] + o.y, pz[t] + o.z} : V3{px[t], py[t], pz[t]};
    normal[a] = {sign * nx[t], sign * ny[t], sign * nz[t]};
  }
}

}  // namespace sdb::mipgh
