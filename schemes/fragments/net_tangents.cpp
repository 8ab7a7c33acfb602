// The limit tangents of a shape's output as weights on its level-0 slots.
//
// A tangent taken from the last level's points, as Far's masks are, inherits their rounding:
// every level adds an ulp of the coordinates (relative to the control box, the size of the
// mesh) to points that lie half as far apart as the level before, so the normal loses a bit a
// level, two at a Loop vertex of valence 3, whose ring shrinks by a quarter. On the sword at
// depth 4 that was 0.11 degrees from the reference. The tangent is a fixed linear function of the
// control points, so it can be taken there instead: the same masks, composed with the levels'
// rules in double here, give weights on the level-0 slots; the kernel applies them to the control
// points relative to the fragment's first, which float holds to its full precision.
#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "schemes/fragments/table_builder.h"

namespace sdb::fragments::detail {
namespace {

// One row per slot of a level: its point as weights on the level-0 slots.
class NetRows {
 public:
  NetRows(uint32_t slots, uint32_t n) : n_(n), rows_(size_t(slots) * n, 0.0) {}
  double* row(uint32_t slot) { return rows_.data() + size_t(slot) * n_; }
  const double* row(uint32_t slot) const { return rows_.data() + size_t(slot) * n_; }
  // row(to) += w * from.row(slot)
  void add(uint32_t to, double w, const NetRows& from, uint32_t slot) {
    double* r = row(to);
    const double* f = from.row(slot);
    for (uint32_t j = 0; j < n_; ++j) r[j] += w * f[j];
  }

 private:
  uint32_t n_;
  std::vector<double> rows_;
};

// kernel.cpp's refine_level on rows instead of points.
NetRows refine_rows(const LevelTable& t, bool catmark, const NetRows& parent, uint32_t n) {
  NetRows child(t.num_slots, n);
  uint32_t out = 0;
  for (const FaceRule& f : t.faces) {
    for (uint32_t s : {f.a, f.b, f.c, f.d}) child.add(out, 0.25, parent, s);
    ++out;
  }
  const NetRows& opposite = catmark ? child : parent;
  for (const EdgeRule& e : t.edges) {
    child.add(out, e.wv, parent, e.v0), child.add(out, e.wv, parent, e.v1);
    if (e.wf != 0) child.add(out, e.wf, opposite, e.f0), child.add(out, e.wf, opposite, e.f1);
    ++out;
  }
  for (const VertexRule& v : t.vertices) {
    child.add(out, v.wv, parent, v.centre);
    if (v.wc != 0) child.add(out, v.wc, parent, v.p0), child.add(out, v.wc, parent, v.p1);
    for (uint32_t k = 0; k < v.num_e; ++k) child.add(out, v.we, parent, t.ring[v.ring + k]);
    for (uint32_t k = 0; k < v.num_f; ++k) child.add(out, v.wf, opposite, t.ring[v.ring + v.num_e + k]);
    ++out;
  }
  return child;
}

void add_patch_polynomial(ShapeTables& t, bool catmark, const NetRows& last);

void add_net_support(ShapeTables& t) {
  LimitTable& lim = t.limit;
  const uint32_t n = lim.net_size;
  const size_t per_block = t.block_vertices() / t.owned_faces;
  lim.net_support_begin = {0};
  for (int b = 0; b < t.owned_faces; ++b) {
    for (uint32_t j = 1; j < n; ++j) {
      bool weighed = false;
      for (size_t i = b * per_block; i < (b + 1) * per_block && !weighed; ++i)
        weighed = lim.net_tangents[i * 2 * n + j] != 0 || lim.net_tangents[i * 2 * n + n + j] != 0;
      if (weighed) lim.net_support.push_back(j);
    }
    lim.net_support_begin.push_back(static_cast<uint32_t>(lim.net_support.size()));
  }
}

}  // namespace

void add_net_tangents(ShapeTables& t, bool catmark) {
  LimitTable& lim = t.limit;
  const uint32_t n = t.num_slots0;
  if (n > kMaxTangentNet) return;
  NetRows rows(n, n);
  for (uint32_t j = 0; j < n; ++j) rows.row(j)[j] = 1.0;
  for (const LevelTable& level : t.levels) rows = refine_rows(level, catmark, rows, n);
  const size_t entries = lim.regular.size();
  lim.net_size = n;
  lim.net_tangents.assign(entries * 2 * n, 0.0f);
  std::vector<double> a(n), b(n);
  for (size_t i = 0; i < entries; ++i) {
    std::fill(a.begin(), a.end(), 0.0), std::fill(b.begin(), b.end(), 0.0);
    auto take = [&](uint32_t slot, double w1, double w2) {
      const double* r = rows.row(slot);
      for (uint32_t j = 0; j < n; ++j) a[j] += w1 * r[j], b[j] += w2 * r[j];
    };
    if (lim.regular[i] >= 0) {
      const uint32_t* slots = lim.regular_slots.data() + size_t(lim.regular[i]) * lim.regular_size;
      const RegularTangents& w = regular_tangents(catmark);
      for (int k = 0; k < lim.regular_size; ++k) take(slots[k], w.first[k], w.second[k]);
    } else {
      for (uint32_t k = lim.tangent_begin[i]; k < lim.tangent_begin[i + 1]; ++k)
        take(lim.tangent_slot[k], lim.tangent_w1[k], lim.tangent_w2[k]);
    }
    float* out = lim.net_tangents.data() + i * 2 * n;
    for (uint32_t j = 0; j < n; ++j) out[j] = static_cast<float>(a[j]), out[n + j] = static_cast<float>(b[j]);
  }
  add_net_support(t);
  add_patch_polynomial(t, catmark, rows);
}

namespace {

// LimitTable::patch_*: the limit positions of the block as weights on the net (the last level's
// rows through each position rule), fitted by a polynomial in (u, v). The tangent masks' own
// directions turn with each vertex's ring, so the positions are what is fitted.
void add_patch_polynomial(ShapeTables& t, bool catmark, const NetRows& last) {
  LimitTable& lim = t.limit;
  const uint32_t n = lim.net_size;
  const SubdivisionRule rule = catmark ? SubdivisionRule::CatmullClark : SubdivisionRule::Loop;
  if (t.owned_faces != 1) return;
  int s = 0;
  while (block_size(rule, s) < static_cast<int>(t.block_vertices())) ++s;
  for (int32_t stencil : lim.stencil)
    if (stencil >= 0) return;  // a dart's position: not a regular patch
  std::vector<std::array<uint8_t, 2>> powers;  // the order kernel.cpp's row_coefficients unrolls (tables.h)
  for (int a = 0; a <= 4; ++a)
    for (int b = 0; b <= 4; ++b)
      if (catmark ? a <= 3 && b <= 3 : a + b <= 4) powers.push_back({uint8_t(a), uint8_t(b)});
  const int segments = 1 << s, m = static_cast<int>(powers.size());
  const size_t entries = t.block_vertices();
  Eigen::MatrixXd basis(entries, m), positions(entries, n);
  for (int j = 0; j <= segments; ++j)
    for (int i = 0; i + (catmark ? 0 : j) <= segments; ++i) {
      const int e = block_index(rule, s, i, j);
      for (int k = 0; k < m; ++k)
        basis(e, k) = std::pow(double(i) / segments, powers[k][0]) * std::pow(double(j) / segments, powers[k][1]);
      const VertexRule& r = lim.position[e];
      NetRows p(1, n);
      p.add(0, r.wv, last, r.centre);
      if (r.wc != 0) p.add(0, r.wc, last, r.p0), p.add(0, r.wc, last, r.p1);
      for (uint32_t k = 0; k < r.num_e; ++k) p.add(0, r.we, last, lim.ring[r.ring + k]);
      for (uint32_t k = 0; k < r.num_f; ++k) p.add(0, r.wf, last, lim.ring[r.ring + r.num_e + k]);
      for (uint32_t w = 0; w < n; ++w) positions(e, w) = p.row(0)[w];
    }
  if (static_cast<int>(entries) < m) return;
  const Eigen::MatrixXd c = basis.colPivHouseholderQr().solve(positions);
  if ((basis * c - positions).cwiseAbs().maxCoeff() > 1e-9 * positions.cwiseAbs().maxCoeff()) return;
  // A fit can pass where the block has no more points than monomials (Loop at depth 2): the
  // polynomial's normals must also be the masks' (net_tangents) on random control points.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  for (int trial = 0; trial < 3; ++trial) {
    Eigen::MatrixXd points(n, 3);
    for (uint32_t w = 0; w < n; ++w)
      for (int x = 0; x < 3; ++x) points(w, x) = coordinate(random);
    const Eigen::MatrixXd coefficients = c * points;  // monomial x xyz
    for (int j = 0; j <= segments; ++j)
      for (int i = 0; i + (catmark ? 0 : j) <= segments; ++i) {
        const double u = double(i) / segments, v = double(j) / segments;
        Eigen::Vector3d du = Eigen::Vector3d::Zero(), dv = Eigen::Vector3d::Zero(), a = du, b = du;
        for (int k = 0; k < m; ++k) {
          const int pa = powers[k][0], pb = powers[k][1];
          if (pa > 0) du += pa * std::pow(u, pa - 1) * std::pow(v, pb) * coefficients.row(k).transpose();
          if (pb > 0) dv += pb * std::pow(u, pa) * std::pow(v, pb - 1) * coefficients.row(k).transpose();
        }
        const float* w = lim.net_tangents.data() + size_t(block_index(rule, s, i, j)) * 2 * n;
        for (uint32_t q = 0; q < n; ++q) a += double(w[q]) * points.row(q).transpose(), b += double(w[n + q]) * points.row(q).transpose();
        const Eigen::Vector3d ours = du.cross(dv), theirs = a.cross(b);
        const double dot = ours.dot(theirs);
        if (dot <= 0 || dot * dot < (1 - 1e-9) * ours.squaredNorm() * theirs.squaredNorm()) return;
      }
  }
  lim.patch_segments = segments;
  lim.patch_triangle = !catmark;
  lim.patch_weights.resize(size_t(m) * n);
  for (int k = 0; k < m; ++k)
    for (uint32_t w = 0; w < n; ++w) lim.patch_weights[size_t(k) * n + w] = static_cast<float>(c(k, w));
}

}  // namespace

const RegularTangents& regular_tangents(bool catmark) {
  // Sdc's regular tangent masks (centre, ring, opposite vertices), which kernel.cpp's
  // regular_normal() writes as differences.
  static const RegularTangents cc = {{0, 4, 0, -4, 0, 1, -1, -1, 1}, {0, 0, 4, 0, -4, 1, 1, -1, -1}};
  static const double h = std::sqrt(3.0) / 2;
  static const RegularTangents loop = {{0, 1, 0.5, -0.5, -1, -0.5, 0.5}, {0, 0, h, h, 0, -h, -h}};
  return catmark ? cc : loop;
}

}  // namespace sdb::fragments::detail
