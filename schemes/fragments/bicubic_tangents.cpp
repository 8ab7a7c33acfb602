// The bicubic fast path of a regular Catmull-Clark facet patch's tangents (tables.h,
// LimitTable::bicubic_*): the 4 x 4 control points found from the net's topology, the uniform
// cubic B-spline basis at the output's grid.
#include <array>
#include <cmath>
#include <random>

#include "schemes/fragments/table_builder.h"

namespace sdb::fragments::detail {
namespace {

// Uniform cubic B-spline basis and its derivative at t in [0, 1].
void bspline(double t, double b[4], double d[4]) {
  const double s = 1 - t;
  b[0] = s * s * s / 6, b[1] = (3 * t * t * t - 6 * t * t + 4) / 6, b[2] = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6,
  b[3] = t * t * t / 6;
  d[0] = -s * s / 2, d[1] = (3 * t * t - 4 * t) / 2, d[2] = (-3 * t * t + 2 * t + 1) / 2, d[3] = t * t / 2;
}

// The neighbour of v across from u (v of valence 4): the other end of the edge two places on.
int across(const Far::TopologyLevel& l, int v, int u) {
  Far::ConstIndexArray ve = l.GetVertexEdges(v);
  for (int k = 0; k < 4; ++k) {
    Far::ConstIndexArray ends = l.GetEdgeVertices(ve[k]);
    if ((ends[0] == v ? ends[1] : ends[0]) != u) continue;
    Far::ConstIndexArray far = l.GetEdgeVertices(ve[(k + 2) % 4]);
    return far[0] == v ? far[1] : far[0];
  }
  return -1;
}

// The vertex of the quad holding a, b and c (three corners of it) that is none of them.
int fourth(const Far::TopologyLevel& l, int a, int b, int c) {
  for (int f : l.GetVertexFaces(a)) {
    Far::ConstIndexArray fv = l.GetFaceVertices(f);
    int found = 0, other = -1;
    for (int x : fv) (x == a || x == b || x == c) ? ++found : other = x;
    if (found == 3 && fv.size() == 4) return other;
  }
  return -1;
}

std::array<double, 3> cross(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

}  // namespace

template <Sdc::SchemeType S>
void TableBuilder<S>::add_bicubic_tangents(ShapeTables& t) const {
  const Far::TopologyLevel& l = refiner_->GetLevel(0);
  LimitTable& lim = t.limit;
  if (num_owned_ != 1 || !t.block_in_order || lim.net_size == 0 || l.GetNumFaces() != 9 || l.GetNumVertices() != 16)
    return;
  for (int v = 0; v < l.GetNumVertices(); ++v)
    if (l.GetVertexSharpness(v) > 0) return;
  for (int e = 0; e < l.GetNumEdges(); ++e)
    if (l.GetEdgeSharpness(e) > 0 && !l.IsEdgeBoundary(e)) return;
  for (int f = 0; f < l.GetNumFaces(); ++f)
    if (l.IsFaceHole(f)) return;
  Far::ConstIndexArray q = l.GetFaceVertices(0);  // the owned face, in ptex order
  for (int v : q)
    if (l.IsVertexBoundary(v) || l.GetVertexEdges(v).size() != 4 || l.GetVertexRule(v) != Sdc::Crease::RULE_SMOOTH) return;
  // P[a][b], a along u (q0 -> q1), b along v (q0 -> q3); the owned face is P[1..2][1..2].
  int p[4][4];
  p[1][1] = q[0], p[2][1] = q[1], p[2][2] = q[2], p[1][2] = q[3];
  p[0][1] = across(l, q[0], q[1]), p[1][0] = across(l, q[0], q[3]);
  p[3][1] = across(l, q[1], q[0]), p[2][0] = across(l, q[1], q[2]);
  p[3][2] = across(l, q[2], q[3]), p[2][3] = across(l, q[2], q[1]);
  p[0][2] = across(l, q[3], q[2]), p[1][3] = across(l, q[3], q[0]);
  p[0][0] = fourth(l, q[0], p[0][1], p[1][0]), p[3][0] = fourth(l, q[1], p[3][1], p[2][0]);
  p[3][3] = fourth(l, q[2], p[3][2], p[2][3]), p[0][3] = fourth(l, q[3], p[0][2], p[1][3]);
  std::vector<uint32_t> slots(16);
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      if (p[a][b] < 0) return;
      slots[4 * a + b] = static_cast<uint32_t>(p[a][b]);
    }
  const int s = 1 << out_depth_, n = s + 1;
  std::vector<double> basis(8 * n);
  for (int k = 0; k <= s; ++k) bspline(double(k) / s, &basis[8 * k], &basis[8 * k + 4]);
  // The same normals as the net's tangents give, on random control points, or no fast path.
  const uint32_t m = lim.net_size;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<std::array<double, 3>> points(m);
    for (auto& x : points) x = {coordinate(random), coordinate(random), coordinate(random)};
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        std::array<double, 3> su{}, sv{}, a{}, b{};
        for (int c = 0; c < 4; ++c)
          for (int d = 0; d < 4; ++d)
            for (int x = 0; x < 3; ++x) {
              const double pt = points[slots[4 * c + d]][x];
              su[x] += basis[8 * i + 4 + c] * basis[8 * j + d] * pt, sv[x] += basis[8 * i + c] * basis[8 * j + 4 + d] * pt;
            }
        const float* w = lim.net_tangents.data() + size_t(j * n + i) * 2 * m;
        for (uint32_t k = 0; k < m; ++k)
          for (int x = 0; x < 3; ++x) a[x] += w[k] * points[k][x], b[x] += w[m + k] * points[k][x];
        const std::array<double, 3> ours = cross(su, sv), theirs = cross(a, b);
        const double dot = ours[0] * theirs[0] + ours[1] * theirs[1] + ours[2] * theirs[2];
        const double nn = ours[0] * ours[0] + ours[1] * ours[1] + ours[2] * ours[2];
        const double tt = theirs[0] * theirs[0] + theirs[1] * theirs[1] + theirs[2] * theirs[2];
        if (dot <= 0 || dot * dot < (1 - 1e-9) * nn * tt) return;
      }
  }
  lim.bicubic_slots = std::move(slots);
  lim.bicubic_basis.assign(basis.begin(), basis.end());
}

template void TableBuilder<Sdc::SCHEME_CATMARK>::add_bicubic_tangents(ShapeTables&) const;
template void TableBuilder<Sdc::SCHEME_LOOP>::add_bicubic_tangents(ShapeTables&) const;

}  // namespace sdb::fragments::detail
