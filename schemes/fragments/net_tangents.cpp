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
#include <cmath>

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
}

const RegularTangents& regular_tangents(bool catmark) {
  // Sdc's regular tangent masks (centre, ring, opposite vertices), which kernel.cpp's
  // regular_normal() writes as differences.
  static const RegularTangents cc = {{0, 4, 0, -4, 0, 1, -1, -1, 1}, {0, 0, 4, 0, -4, 1, 1, -1, -1}};
  static const double h = std::sqrt(3.0) / 2;
  static const RegularTangents loop = {{0, 1, 0.5, -0.5, -1, -0.5, 0.5}, {0, 0, h, h, 0, -h, -h}};
  return catmark ? cc : loop;
}

}  // namespace sdb::fragments::detail
