#include "schemes/fragments/kernel.h"

#include <algorithm>
#include <cmath>

#ifdef __SSE__
#include <immintrin.h>
#endif

namespace sdb::fragments {
namespace {

#define SDB_LANES _Pragma("omp simd") for (int l = 0; l < W; ++l)

// a + b, lane by lane.
template <int W>
inline Lanes<W> add(const Lanes<W>& a, const Lanes<W>& b) {
  Lanes<W> r;
  SDB_LANES r.x[l] = a.x[l] + b.x[l], r.y[l] = a.y[l] + b.y[l], r.z[l] = a.z[l] + b.z[l];
  return r;
}
template <int W>
inline Lanes<W> sub(const Lanes<W>& a, const Lanes<W>& b) {
  Lanes<W> r;
  SDB_LANES r.x[l] = a.x[l] - b.x[l], r.y[l] = a.y[l] - b.y[l], r.z[l] = a.z[l] - b.z[l];
  return r;
}
template <int W>
inline Lanes<W> scale(const Lanes<W>& a, float s) {
  Lanes<W> r;
  SDB_LANES r.x[l] = a.x[l] * s, r.y[l] = a.y[l] * s, r.z[l] = a.z[l] * s;
  return r;
}

// Adding +0 first turns -0 into +0: min and max cannot order two zeros, so without it the sum
// of {-0, +0, x} would depend on which came first.
inline float sum3_sorted(float a, float b, float c) {
  a += 0.0f, b += 0.0f, c += 0.0f;
  const float lo = std::min(std::min(a, b), c), hi = std::max(std::max(a, b), c);
  const float mid = std::max(std::min(a, b), std::min(std::max(a, b), c));
  return (lo + mid) + hi;
}

// Ascending, so the sum is the same whatever order the terms came in.
float sorted_sum(float* v, int n) {
  for (int i = 0; i < n; ++i) v[i] += 0.0f;
  std::sort(v, v + n);
  float s = v[0];
  for (int i = 1; i < n; ++i) s += v[i];
  return s;
}

// The same sum for short rings, all lanes at once: an odd-even transposition sort (n passes of
// compare-exchanges, min and max on whole lane vectors), then the ascending sum.
constexpr int kNetworkRing = 12;

template <int W>
void sorted_sum_lanes(const Lanes<W>* src, const uint32_t* ref, int n, Lanes<W>& out) {
  float v[kNetworkRing][W];
  for (int axis = 0; axis < 3; ++axis) {
    for (int i = 0; i < n; ++i) {
      const Lanes<W>& p = src[ref[i]];
      const float* c = axis == 0 ? p.x : axis == 1 ? p.y : p.z;
      SDB_LANES v[i][l] = c[l] + 0.0f;
    }
    for (int pass = 0; pass < n; ++pass)
      for (int i = pass & 1; i + 1 < n; i += 2)
        SDB_LANES {
          const float a = v[i][l], b = v[i + 1][l];
          v[i][l] = std::min(a, b), v[i + 1][l] = std::max(a, b);
        }
    float* o = axis == 0 ? out.x : axis == 1 ? out.y : out.z;
    SDB_LANES o[l] = v[0][l];
    for (int i = 1; i < n; ++i) SDB_LANES o[l] += v[i][l];
  }
}

// The sum of a vertex's ring that two fragments starting the ring at different places get
// bit-identical: opposite pairs for valence 4, 6 and 8 (a rotation permutes the pair sums), a
// sorted sum otherwise.
template <int W>
Lanes<W> ring_sum(const Lanes<W>* src, const uint32_t* ref, int n) {
  switch (n) {
    case 1:
      return src[ref[0]];
    case 2:
      return add(src[ref[0]], src[ref[1]]);
    case 4:
      return add(add(src[ref[0]], src[ref[2]]), add(src[ref[1]], src[ref[3]]));
    case 6: {
      const Lanes<W> a = add(src[ref[0]], src[ref[3]]), b = add(src[ref[1]], src[ref[4]]), c = add(src[ref[2]], src[ref[5]]);
      Lanes<W> r;
      SDB_LANES r.x[l] = sum3_sorted(a.x[l], b.x[l], c.x[l]), r.y[l] = sum3_sorted(a.y[l], b.y[l], c.y[l]),
          r.z[l] = sum3_sorted(a.z[l], b.z[l], c.z[l]);
      return r;
    }
    case 8: {
      Lanes<W> q[4];
      for (int i = 0; i < 4; ++i) q[i] = add(src[ref[i]], src[ref[i + 4]]);
      return add(add(q[0], q[2]), add(q[1], q[3]));
    }
    default: {
      Lanes<W> r;
      if (n <= kNetworkRing) {
        sorted_sum_lanes(src, ref, n, r);
        return r;
      }
      float v[1024];  // tables.cpp refuses longer rings
      for (int l = 0; l < W; ++l) {
        for (int i = 0; i < n; ++i) v[i] = src[ref[i]].x[l];
        r.x[l] = sorted_sum(v, n);
        for (int i = 0; i < n; ++i) v[i] = src[ref[i]].y[l];
        r.y[l] = sorted_sum(v, n);
        for (int i = 0; i < n; ++i) v[i] = src[ref[i]].z[l];
        r.z[l] = sorted_sum(v, n);
      }
      return r;
    }
  }
}

template <int W>
inline Lanes<W> apply(const VertexRule& r, const uint32_t* ring, const Lanes<W>* pv, const Lanes<W>* pf) {
  const uint32_t* ref = ring + r.ring;
  Lanes<W> s = scale(pv[r.centre], r.wv);
  if (r.wc != 0) s = add(s, scale(add(pv[r.p0], pv[r.p1]), r.wc));
  if (r.num_e) s = add(s, scale(ring_sum(pv, ref, r.num_e), r.we));
  if (r.num_f) s = add(s, scale(ring_sum(pf, ref + r.num_e, r.num_f), r.wf));
  return s;
}

// 1 / sqrt(v), IEEE-exact in every lane (GCC 12 leaves sqrtf scalar here; SSE's sqrtps and divps
// round as sqrtf and / do, so the bits are the same either way).
template <int W>
inline void inverse_sqrt(float* v) {
#ifdef __SSE__
  if constexpr (W % 4 == 0) {
    for (int l = 0; l < W; l += 4) _mm_storeu_ps(v + l, _mm_div_ps(_mm_set1_ps(1.0f), _mm_sqrt_ps(_mm_loadu_ps(v + l))));
    return;
  }
#endif
  SDB_LANES v[l] = 1.0f / std::sqrt(v[l]);
}

template <int W>
inline void unit_normal(const Lanes<W>& a, const Lanes<W>& b, Lanes<W>& n) {
  Lanes<W> c;
  float len2[W], inv[W];
  SDB_LANES {
    c.x[l] = a.y[l] * b.z[l] - a.z[l] * b.y[l], c.y[l] = a.z[l] * b.x[l] - a.x[l] * b.z[l],
    c.z[l] = a.x[l] * b.y[l] - a.y[l] * b.x[l];
    len2[l] = c.x[l] * c.x[l] + c.y[l] * c.y[l] + c.z[l] * c.z[l];
  }
  SDB_LANES inv[l] = len2[l] > 0 ? len2[l] : 1.0f;
  inverse_sqrt<W>(inv);
  SDB_LANES {
    const float k = len2[l] > 0 ? inv[l] : 0.0f;
    n.x[l] = c.x[l] * k, n.y[l] = c.y[l] * k, n.z[l] = c.z[l] * k;
  }
}

// Sdc's tangents of a regular vertex (tables.cpp checks the weights are these), grouped into
// differences: Catmull-Clark 4 (e0 - e2) + (f0 - f1 - f2 + f3) and 4 (e1 - e3) + (f0 + f1 - f2 - f3);
// Loop (e0 - e3) + (e1 - e2 - e4 + e5) / 2 and sqrt(3) / 2 (e1 + e2 - e4 - e5). Slots: centre, e, f.
template <int W>
inline void regular_normal(const uint32_t* slot, int size, const Lanes<W>* p, Lanes<W>& n) {
  if (size == 9) {
    const Lanes<W> d02 = sub(p[slot[5]], p[slot[7]]), d13 = sub(p[slot[6]], p[slot[8]]);
    unit_normal(add(scale(sub(p[slot[1]], p[slot[3]]), 4.0f), sub(d02, d13)),
                add(scale(sub(p[slot[2]], p[slot[4]]), 4.0f), add(d02, d13)), n);
    return;
  }
  const Lanes<W> d14 = sub(p[slot[2]], p[slot[5]]), d25 = sub(p[slot[3]], p[slot[6]]);
  unit_normal(add(sub(p[slot[1]], p[slot[4]]), scale(sub(d14, d25), 0.5f)), scale(add(d14, d25), 0.866025404f), n);
}

// Tangents are differences of nearby points: long masks (a pole's ring, where the points crowd
// together) are summed in double, so that the normal keeps float precision at valence 360.
constexpr uint32_t kLongTangentMask = 32;

template <int W>
void general_normal(const LimitTable& t, size_t i, const Lanes<W>* last, Lanes<W>& n) {
  const uint32_t begin = t.tangent_begin[i], end = t.tangent_begin[i + 1];
  const uint32_t* slot = t.tangent_slot.data();
  const float *w1 = t.tangent_w1.data(), *w2 = t.tangent_w2.data();
  Lanes<W> a{}, b{};
  if (end - begin > kLongTangentMask) {
    for (int l = 0; l < W; ++l) {
      double da[3] = {0, 0, 0}, db[3] = {0, 0, 0};
      for (uint32_t k = begin; k < end; ++k) {
        const Lanes<W>& p = last[slot[k]];
        da[0] += double(w1[k]) * p.x[l], da[1] += double(w1[k]) * p.y[l], da[2] += double(w1[k]) * p.z[l];
        db[0] += double(w2[k]) * p.x[l], db[1] += double(w2[k]) * p.y[l], db[2] += double(w2[k]) * p.z[l];
      }
      a.x[l] = float(da[0]), a.y[l] = float(da[1]), a.z[l] = float(da[2]);
      b.x[l] = float(db[0]), b.y[l] = float(db[1]), b.z[l] = float(db[2]);
    }
  } else {
    for (uint32_t k = begin; k < end; ++k) {
      const Lanes<W>& p = last[slot[k]];
      SDB_LANES {
        a.x[l] += w1[k] * p.x[l], a.y[l] += w1[k] * p.y[l], a.z[l] += w1[k] * p.z[l];
        b.x[l] += w2[k] * p.x[l], b.y[l] += w2[k] * p.y[l], b.z[l] += w2[k] * p.z[l];
      }
    }
  }
  unit_normal(a, b, n);
}

// The tangents as weights on the control points relative to the first (net[0] is 0).
template <int W>
void net_normal(const float* w1, uint32_t n, const Lanes<W>* net, Lanes<W>& out) {
  const float* w2 = w1 + n;
  Lanes<W> a{}, b{};
  for (uint32_t j = 1; j < n; ++j) {
    const Lanes<W>& p = net[j];
    const float u = w1[j], v = w2[j];
    SDB_LANES {
      a.x[l] += u * p.x[l], a.y[l] += u * p.y[l], a.z[l] += u * p.z[l];
      b.x[l] += v * p.x[l], b.y[l] += v * p.y[l], b.z[l] += v * p.z[l];
    }
  }
  unit_normal(a, b, out);
}

// a += w b, lane by lane.
template <int W>
inline void add_scaled(Lanes<W>& a, float w, const Lanes<W>& b) {
  SDB_LANES a.x[l] += w * b.x[l], a.y[l] += w * b.y[l], a.z[l] += w * b.z[l];
}

// The patch polynomial (tables.h, patch_*): its coefficients from the net once, then per row the
// derivatives' coefficients as cubics in u, then per vertex Horner's rule.
template <int W>
void patch_normals(const LimitTable& t, const Lanes<W>* net, Lanes<W>* normal) {
  const uint32_t n = t.net_size;
  const int s = t.patch_segments, m = static_cast<int>(t.patch_powers.size());
  Lanes<W> c[25];
  for (int k = 0; k < m; ++k) {
    // Summed in a local: through c[k] every step waited on the previous one's store.
    Lanes<W> sum{};
    const float* w = t.patch_weights.data() + size_t(k) * n;
    for (uint32_t slot = 1; slot < n; ++slot) add_scaled(sum, w[slot], net[slot]);
    c[k] = sum;
  }
  for (int j = 0; j <= s; ++j) {
    const float v = float(j) / float(s);
    float vp[5] = {1, v, v * v, v * v * v, v * v * v * v};
    Lanes<W> du[4] = {}, dv[4] = {};  // coefficients of u^0 .. u^3
    for (int k = 0; k < m; ++k) {
      const int a = t.patch_powers[k][0], b = t.patch_powers[k][1];
      if (a > 0) add_scaled(du[a - 1], float(a) * vp[b], c[k]);
      if (b > 0) add_scaled(dv[a], float(b) * vp[b - 1], c[k]);
    }
    const int points = t.patch_triangle ? s + 1 - j : s + 1;
    for (int i = 0; i < points; ++i) {
      const float u = float(i) / float(s);
      Lanes<W> d[2];
      for (int tangent = 0; tangent < 2; ++tangent) {
        const Lanes<W>* p = tangent ? dv : du;
        SDB_LANES {
          d[tangent].x[l] = ((p[3].x[l] * u + p[2].x[l]) * u + p[1].x[l]) * u + p[0].x[l];
          d[tangent].y[l] = ((p[3].y[l] * u + p[2].y[l]) * u + p[1].y[l]) * u + p[0].y[l];
          d[tangent].z[l] = ((p[3].z[l] * u + p[2].z[l]) * u + p[1].z[l]) * u + p[0].z[l];
        }
      }
      unit_normal(d[0], d[1], *normal++);
    }
  }
}

// One fragment: the sums run across the net's slots instead, in the vector lanes (normals need
// not be bit-identical, so their order is free).
template <>
void net_normal<1>(const float* w1, uint32_t n, const Lanes<1>* net, Lanes<1>& out) {
  const float* w2 = w1 + n;
  float ax = 0, ay = 0, az = 0, bx = 0, by = 0, bz = 0;
#pragma omp simd reduction(+ : ax, ay, az, bx, by, bz)
  for (uint32_t j = 1; j < n; ++j) {
    const float x = net[j].x[0], y = net[j].y[0], z = net[j].z[0];
    ax += w1[j] * x, ay += w1[j] * y, az += w1[j] * z;
    bx += w2[j] * x, by += w2[j] * y, bz += w2[j] * z;
  }
  unit_normal(Lanes<1>{{ax}, {ay}, {az}}, Lanes<1>{{bx}, {by}, {bz}}, out);
}

}  // namespace

// AVX2 where the CPU has it, SSE2 otherwise, every helper inlined into each clone
// (flatten) so that the whole pass runs in the wider lanes. Without fused multiply-adds
// (-ffp-contract=off) and with IEEE min, max, sqrt and division in both, the two give the same
// bits: outputs do not depend on the machine.
#define SDB_KERNEL_CLONES __attribute__((target_clones("avx2", "default"), flatten))

template <int W>
SDB_KERNEL_CLONES void refine_level(const LevelTable& t, bool catmark, const Lanes<W>* parent, Lanes<W>* child) {
  Lanes<W>* out = child;
  for (const FaceRule& f : t.faces) {
    const Lanes<W> &a = parent[f.a], &b = parent[f.b], &c = parent[f.c], &d = parent[f.d];
    Lanes<W>& o = *out++;
    SDB_LANES o.x[l] = ((a.x[l] + c.x[l]) + (b.x[l] + d.x[l])) * 0.25f, o.y[l] = ((a.y[l] + c.y[l]) + (b.y[l] + d.y[l])) * 0.25f,
        o.z[l] = ((a.z[l] + c.z[l]) + (b.z[l] + d.z[l])) * 0.25f;
  }
  const Lanes<W>* opposite = catmark ? child : parent;
  for (const EdgeRule& e : t.edges) {
    const Lanes<W> &v0 = parent[e.v0], &v1 = parent[e.v1];
    Lanes<W>& o = *out++;
    // A crease or boundary edge has no face term, and its f slots name no point of this level
    // (tables.h): never read them (0 times a stale NaN is NaN on the GPU).
    if (e.wf == 0) {
      SDB_LANES o.x[l] = (v0.x[l] + v1.x[l]) * e.wv, o.y[l] = (v0.y[l] + v1.y[l]) * e.wv,
          o.z[l] = (v0.z[l] + v1.z[l]) * e.wv;
      continue;
    }
    const Lanes<W> &f0 = opposite[e.f0], &f1 = opposite[e.f1];
    SDB_LANES o.x[l] = (v0.x[l] + v1.x[l]) * e.wv + (f0.x[l] + f1.x[l]) * e.wf,
        o.y[l] = (v0.y[l] + v1.y[l]) * e.wv + (f0.y[l] + f1.y[l]) * e.wf,
        o.z[l] = (v0.z[l] + v1.z[l]) * e.wv + (f0.z[l] + f1.z[l]) * e.wf;
  }
  const uint32_t* ring = t.ring.data();
  for (const VertexRule& v : t.vertices) *out++ = apply(v, ring, parent, opposite);
}

template <int W>
SDB_KERNEL_CLONES void project_to_limit(const LimitTable& t, const Lanes<W>* last, const Lanes<W>* net,
                                        const Lanes<W>* local_last, bool project, Lanes<W>* position,
                                        Lanes<W>* normal) {
  for (size_t i = 0; i < t.position.size(); ++i) {
    if (!project) {
      position[i] = last[t.position[i].centre];
    } else if (t.stencil[i] < 0) {
      position[i] = apply(t.position[i], t.ring.data(), last, last);
    } else {  // in the stencil's order, which every fragment shares
      Lanes<W> p{};
      for (uint32_t k = t.stencil_begin[t.stencil[i]]; k < t.stencil_begin[t.stencil[i] + 1]; ++k)
        p = add(p, scale(last[t.stencil_slot[k]], t.stencil_w[k]));
      position[i] = p;
    }
  }
  if (!t.patch_weights.empty()) return patch_normals(t, net, normal);
  const Lanes<W>* from = local_last ? local_last : last;
  for (size_t i = 0; i < t.regular.size(); ++i) {
    if (t.net_size && (!local_last || t.at_control_vertex[i]))
      net_normal(t.net_tangents.data() + i * 2 * t.net_size, t.net_size, net, normal[i]);
    else if (t.regular[i] >= 0)
      regular_normal(t.regular_slots.data() + static_cast<size_t>(t.regular[i]) * t.regular_size, t.regular_size, from,
                     normal[i]);
    else
      general_normal(t, i, from, normal[i]);
  }
}

template void refine_level<1>(const LevelTable&, bool, const Lanes<1>*, Lanes<1>*);
template void refine_level<kLanes>(const LevelTable&, bool, const Lanes<kLanes>*, Lanes<kLanes>*);
template void project_to_limit<1>(const LimitTable&, const Lanes<1>*, const Lanes<1>*, const Lanes<1>*, bool, Lanes<1>*,
                                  Lanes<1>*);
template void project_to_limit<kLanes>(const LimitTable&, const Lanes<kLanes>*, const Lanes<kLanes>*,
                                       const Lanes<kLanes>*, bool, Lanes<kLanes>*, Lanes<kLanes>*);

}  // namespace sdb::fragments
