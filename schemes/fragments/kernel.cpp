#include "schemes/fragments/kernel.h"

#include "harness/core/errors.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>


// The vector helpers below are inlined into the kernel's clones (flatten): their ABI never matters.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace sdb::fragments {
namespace {

// Eight floats operated on element by element: kLanes lanes of one coordinate, or one Pair. Written
// as a vector type rather than arrays in loops so that values stay in registers (GCC copied
// array structs through the stack and the integer registers).
typedef float F8 __attribute__((vector_size(32)));
typedef float F8u __attribute__((vector_size(32), aligned(4), may_alias));  // unaligned, as the slots are

// A slot's floats: K = 3 vectors (x, y, z of kLanes fragments) or K = 1 (a Pair).
template <int K>
struct V {
  F8 v[K];
};

// The vectors of a level buffer's slot that hold values: Lanes' x y z, a PairSlot's one Pair.
template <class Slot>
constexpr int vectors_of = std::is_same_v<Slot, PairSlot> ? 1 : 3;
static_assert(sizeof(Lanes<kLanes>) == 3 * sizeof(F8) && sizeof(Pair) == sizeof(F8));

template <int K>
inline V<K> operator+(const V<K>& a, const V<K>& b) {
  V<K> r;
  for (int k = 0; k < K; ++k) r.v[k] = a.v[k] + b.v[k];
  return r;
}
template <int K>
inline V<K> operator-(const V<K>& a, const V<K>& b) {
  V<K> r;
  for (int k = 0; k < K; ++k) r.v[k] = a.v[k] - b.v[k];
  return r;
}
template <int K>
inline V<K> operator*(const V<K>& a, float s) {
  V<K> r;
  for (int k = 0; k < K; ++k) r.v[k] = a.v[k] * s;
  return r;
}

// A level buffer's slots as K-vector values, kSlotBytes apart. The tables name them by byte
// offset (address_in_bytes), so that a table entry is a load's displacement as it stands.
template <int K>
struct Slots {
  const char* base;
  const F8u* at(uint32_t offset) const { return reinterpret_cast<const F8u*>(base + offset); }
  V<K> operator[](uint32_t offset) const {
    const F8u* slot = at(offset);  // one address, the vectors at displacements
    V<K> r;
    for (int k = 0; k < K; ++k) r.v[k] = slot[k];
    return r;
  }
  V<K> slot(uint32_t i) const { return (*this)[i * kSlotBytes]; }  // the i-th, counting in order
};
template <int K>
inline void store(void* to, const V<K>& a) {
  for (int k = 0; k < K; ++k) static_cast<F8u*>(to)[k] = a.v[k];
}

// std::min and std::max, element by element.
inline F8 vmin(F8 a, F8 b) { return b < a ? b : a; }
inline F8 vmax(F8 a, F8 b) { return a < b ? b : a; }

// a + b + c the same whatever order the three come in: the largest of the three ways to add them
// (each pair first, then the third), a set that any reordering leaves as it is. Eight operations
// where sorting the three took eleven. No zero-sign care needed: a sum is -0 only when all three
// are, and then every way gives -0.
inline F8 sum3_symmetric(F8 a, F8 b, F8 c) { return vmax(vmax((a + b) + c, (b + c) + a), (c + a) + b); }

// Ascending, so the sum is the same whatever order the terms came in.
float sorted_sum(float* v, int n) {
  for (int i = 0; i < n; ++i) v[i] += 0.0f;
  std::sort(v, v + n);
  float s = v[0];
  for (int i = 1; i < n; ++i) s += v[i];
  return s;
}

// The same sum for short rings, all elements at once: an odd-even transposition sort (n passes of
// compare-exchanges, min and max on whole vectors), then the ascending sum.
constexpr int kNetworkRing = 12;

template <int K>
V<K> sorted_sum_network(Slots<K> src, const uint32_t* ref, int n) {
  V<K> out;
  for (int k = 0; k < K; ++k) {
    F8 v[kNetworkRing];
    for (int i = 0; i < n; ++i) v[i] = src.at(ref[i])[k] + 0.0f;
    for (int pass = 0; pass < n; ++pass)
      for (int i = pass & 1; i + 1 < n; i += 2) {
        const F8 a = v[i], b = v[i + 1];
        v[i] = vmin(a, b), v[i + 1] = vmax(a, b);
      }
    F8 s = v[0];
    for (int i = 1; i < n; ++i) s += v[i];
    out.v[k] = s;
  }
  return out;
}

template <int K>
V<K> sorted_sum_long(Slots<K> src, const uint32_t* ref, int n) {
  V<K> out;
  float v[1024];  // tables.cpp refuses longer rings
  for (int k = 0; k < K; ++k)
    for (int e = 0; e < 8; ++e) {
      for (int i = 0; i < n; ++i) v[i] = src.at(ref[i])[k][e];
      out.v[k][e] = sorted_sum(v, n);
    }
  return out;
}

// The sum of a vertex's ring that two fragments starting the ring at different places get
// bit-identical: opposite pairs for valence 4, 6 and 8 (a rotation permutes the pair sums), a
// sorted sum otherwise.
template <int K>
V<K> ring_sum(Slots<K> src, const uint32_t* ref, int n) {
  switch (n) {
    case 1:
      return src[ref[0]];
    case 2:
      return src[ref[0]] + src[ref[1]];
    case 4:
      return (src[ref[0]] + src[ref[2]]) + (src[ref[1]] + src[ref[3]]);
    case 6: {
      const V<K> a = src[ref[0]] + src[ref[3]], b = src[ref[1]] + src[ref[4]], c = src[ref[2]] + src[ref[5]];
      V<K> r;
      for (int k = 0; k < K; ++k) r.v[k] = sum3_symmetric(a.v[k], b.v[k], c.v[k]);
      return r;
    }
    case 8: {
      V<K> q[4];
      for (int i = 0; i < 4; ++i) q[i] = src[ref[i]] + src[ref[i + 4]];
      return (q[0] + q[2]) + (q[1] + q[3]);
    }
    default:
      return n <= kNetworkRing ? sorted_sum_network(src, ref, n) : sorted_sum_long(src, ref, n);
  }
}

template <int K>
inline V<K> apply(const VertexRule& r, const uint32_t* ring, Slots<K> pv, Slots<K> pf) {
  const uint32_t* ref = ring + r.ring;
  V<K> s = pv[r.centre] * r.wv;
  if (r.wc != 0) s = s + (pv[r.p0] + pv[r.p1]) * r.wc;
  if (r.num_e) s = s + ring_sum(pv, ref, r.num_e) * r.we;
  if (r.num_f) s = s + ring_sum(pf, ref + r.num_e, r.num_f) * r.wf;
  return s;
}

// apply() without its branches for the smooth regular vertex (Loop's valence 6, Catmull-Clark's 4
// with its face points), nearly every vertex rule and limit position: the same terms in the same
// order.
template <int K>
inline V<K> apply_regular_first(const VertexRule& r, const uint32_t* ring, Slots<K> pv, Slots<K> pf) {
  const uint32_t* ref = ring + r.ring;
  if (r.wc == 0 && r.num_e == 6 && r.num_f == 0) return pv[r.centre] * r.wv + ring_sum(pv, ref, 6) * r.we;
  if (r.wc == 0 && r.num_e == 4 && r.num_f == 4)
    return (pv[r.centre] * r.wv + ring_sum(pv, ref, 4) * r.we) + ring_sum(pf, ref + 4, 4) * r.wf;
  return apply(r, ring, pv, pf);
}

template <class Slot>
Slots<vectors_of<Slot>> slots(const Slot* p) {
  static_assert(sizeof(Slot) == kSlotBytes);
  return {reinterpret_cast<const char*>(p)};
}

// 1 / sqrt(v), IEEE-exact in every element: as a loop GCC vectorizes it (vsqrtps and vdivps on
// all eight under AVX; the SSE intrinsics this replaced took two halves), and sqrtps and divps
// round as sqrtf and / do, so the bits are the same either way.
inline F8 inverse_sqrt(F8 v) {
  float a[8];
  std::memcpy(a, &v, sizeof v);
#pragma omp simd
  for (int l = 0; l < 8; ++l) a[l] = 1.0f / std::sqrt(a[l]);
  std::memcpy(&v, a, sizeof v);
  return v;
}

// The unit normal a x b / |a x b| (0 where a x b is), x y z in vectors 0 1 2: kLanes fragments.
inline void unit_normal(const V<3>& a, const V<3>& b, Lanes<kLanes>& n) {
  const F8 cx = a.v[1] * b.v[2] - a.v[2] * b.v[1], cy = a.v[2] * b.v[0] - a.v[0] * b.v[2],
           cz = a.v[0] * b.v[1] - a.v[1] * b.v[0];
  const F8 len2 = cx * cx + cy * cy + cz * cz;
  const F8 zero = {}, one = zero + 1.0f;
  const F8 k = len2 > zero ? inverse_sqrt(len2 > zero ? len2 : one) : zero;
  store(&n, V<3>{{cx * k, cy * k, cz * k}});
}

// The same for one fragment, from the floats at `h` (a Pair's half).
inline void unit_normal(const V<1>& a, const V<1>& b, int h, Lanes<1>& n) {
  const float ax = a.v[0][h], ay = a.v[0][h + 1], az = a.v[0][h + 2];
  const float bx = b.v[0][h], by = b.v[0][h + 1], bz = b.v[0][h + 2];
  const float cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
  const float len2 = cx * cx + cy * cy + cz * cz;
  const float k = len2 > 0 ? 1.0f / std::sqrt(len2) : 0.0f;
  n = {{cx * k}, {cy * k}, {cz * k}};
}

// Sdc's tangents of a regular vertex (tables.cpp checks the weights are these), grouped into
// differences: Catmull-Clark 4 (e0 - e2) + (f0 - f1 - f2 + f3) and 4 (e1 - e3) + (f0 + f1 - f2 - f3);
// Loop (e0 - e3) + (e1 - e2 - e4 + e5) / 2 and sqrt(3) / 2 (e1 + e2 - e4 - e5). Slots: centre, e, f.
template <int K>
inline void regular_tangents(const uint32_t* slot, int size, Slots<K> p, V<K>& a, V<K>& b) {
  if (size == 9) {
    const V<K> d02 = p[slot[5]] - p[slot[7]], d13 = p[slot[6]] - p[slot[8]];
    a = (p[slot[1]] - p[slot[3]]) * 4.0f + (d02 - d13);
    b = (p[slot[2]] - p[slot[4]]) * 4.0f + (d02 + d13);
    return;
  }
  const V<K> d14 = p[slot[2]] - p[slot[5]], d25 = p[slot[3]] - p[slot[6]];
  a = (p[slot[1]] - p[slot[4]]) + (d14 - d25) * 0.5f;
  b = (d14 + d25) * 0.866025404f;
}

// Tangents are differences of nearby points: long masks (a pole's ring, where the points crowd
// together) are summed in double, so that the normal keeps float precision at valence 360.
constexpr uint32_t kLongTangentMask = 32;

template <int K>
void general_tangents(const LimitTable& t, size_t i, Slots<K> last, V<K>& a, V<K>& b) {
  const uint32_t begin = t.tangent_begin[i], end = t.tangent_begin[i + 1];
  const uint32_t* slot = t.tangent_slot.data();
  const float *w1 = t.tangent_w1.data(), *w2 = t.tangent_w2.data();
  a = {}, b = {};
  if (end - begin > kLongTangentMask) {
    for (int k = 0; k < K; ++k)
      for (int e = 0; e < 8; ++e) {
        double da = 0, db = 0;
        for (uint32_t j = begin; j < end; ++j) {
          const float p = last.at(slot[j])[k][e];
          da += double(w1[j]) * p, db += double(w2[j]) * p;
        }
        a.v[k][e] = float(da), b.v[k][e] = float(db);
      }
    return;
  }
  for (uint32_t j = begin; j < end; ++j) {
    const V<K> p = last[slot[j]];
    a = a + p * w1[j], b = b + p * w2[j];
  }
}

// The tangents as weights on the control points relative to the first, the block's support
// (tables.h, net_support) alone.
void net_normal(const float* w1, uint32_t n, const uint32_t* support, uint32_t count, Slots<3> net,
                Lanes<kLanes>& out) {
  const float* w2 = w1 + n;
  V<3> a{}, b{};
  for (uint32_t k = 0; k < count; ++k) {
    const uint32_t j = support[k];
    const V<3> p = net.slot(j);
    a = a + p * w1[j], b = b + p * w2[j];
  }
  unit_normal(a, b, out);
}

void net_normals(const LimitTable& t, Slots<3> net, Lanes<kLanes>* normal) {
  const uint32_t n = t.net_size, blocks = static_cast<uint32_t>(t.net_support_begin.size() - 1);
  const size_t per_block = t.regular.size() / blocks;
  const float* weights = t.net_tangents.data();
  for (uint32_t b = 0; b < blocks; ++b) {
    const uint32_t* support = t.net_support.data() + t.net_support_begin[b];
    const uint32_t count = t.net_support_begin[b + 1] - t.net_support_begin[b];
    for (size_t i = b * per_block; i < (b + 1) * per_block; ++i)
      net_normal(weights + i * 2 * n, n, support, count, net, normal[i]);
  }
}

// One fragment: the sums run across the net's slots instead, in the vector lanes (normals need
// not be bit-identical, so their order is free).
void net_normal(const float* w1, uint32_t n, const Lanes<1>* net, Lanes<1>& out) {
  const float* w2 = w1 + n;
  float ax = 0, ay = 0, az = 0, bx = 0, by = 0, bz = 0;
#pragma omp simd reduction(+ : ax, ay, az, bx, by, bz)
  for (uint32_t j = 1; j < n; ++j) {
    const float x = net[j].x[0], y = net[j].y[0], z = net[j].z[0];
    ax += w1[j] * x, ay += w1[j] * y, az += w1[j] * z;
    bx += w2[j] * x, by += w2[j] * y, bz += w2[j] * z;
  }
  unit_normal(V<1>{{F8{ax, ay, az}}}, V<1>{{F8{bx, by, bz}}}, 0, out);
}

// A row's derivative coefficients: du[a - 1] = sum of a v^b c[k], dv[a] = sum of b v^(b - 1) c[k]
// over the monomials k = u^a v^b in net_tangents.cpp's order (a-major: a + b <= 4 for Loop's
// triangle, a, b <= 3 for a bicubic), each coefficient's terms summed from 0 in the order of k.
// The monomials are fixed per patch kind, so the loops unroll to straight code (a loop over the
// table's powers, with its branches, was a twelfth of the kernel's instructions).
template <bool kTriangle, int K>
inline void row_coefficients(const V<K>* c, const float* vp, V<K>* du, V<K>* dv) {
  constexpr int kMaxA = kTriangle ? 4 : 3;
  int k = 0;
#pragma GCC unroll 5
  for (int a = 0; a <= kMaxA; ++a) {
    V<K> su{}, sv{};
#pragma GCC unroll 5
    for (int b = 0; b <= (kTriangle ? 4 - a : 3); ++b, ++k) {
      if (a > 0) su = su + c[k] * (float(a) * vp[b]);
      if (b > 0) sv = sv + c[k] * (float(b) * vp[b - 1]);
    }
    if (a > 0) du[a - 1] = su;
    if (a < 4) dv[a] = sv;
  }
  if (!kTriangle) du[3] = V<K>{};
}

// The patch polynomial (tables.h, patch_*): its coefficients from the net once, then per row the
// derivatives' coefficients as cubics in u, then per vertex Horner's rule. `emit(a, b)` takes each
// vertex's two tangents. The table's vectors are read into locals first: stores through the
// may_alias vectors would make the compiler reload them after every store.
template <bool kTriangle, int K, class Emit>
void patch_tangents_of(const LimitTable& t, Slots<K> net, Emit emit) {
  constexpr int m = kTriangle ? 15 : 16;  // the monomials (row_coefficients)
  const uint32_t n = t.net_size;
  const int s = t.patch_segments;
  const float* weights = t.patch_weights.data();
  V<K> c[m];
  for (int k = 0; k < m; ++k) {
    V<K> sum{};
    const float* w = weights + size_t(k) * n;
    for (uint32_t slot = 1; slot < n; ++slot) sum = sum + net.slot(slot) * w[slot];
    c[k] = sum;
  }
  for (int j = 0; j <= s; ++j) {
    const float v = float(j) / float(s);
    float vp[5] = {1, v, v * v, v * v * v, v * v * v * v};
    V<K> du[4], dv[4];  // coefficients of u^0 .. u^3
    row_coefficients<kTriangle>(c, vp, du, dv);
    const int points = kTriangle ? s + 1 - j : s + 1;
    for (int i = 0; i < points; ++i) {
      const float u = float(i) / float(s);
      emit(((du[3] * u + du[2]) * u + du[1]) * u + du[0], ((dv[3] * u + dv[2]) * u + dv[1]) * u + dv[0]);
    }
  }
}

template <int K, class Emit>
void patch_tangents(const LimitTable& t, Slots<K> net, Emit emit) {
  if (t.patch_triangle) return patch_tangents_of<true>(t, net, emit);
  patch_tangents_of<false>(t, net, emit);
}

// A LimitTable's tangent entries, read into locals once (see patch_tangents).
struct TangentView {
  explicit TangentView(const LimitTable& t)
      : size(t.regular.size()), regular(t.regular.data()), regular_slots(t.regular_slots.data()),
        regular_size(t.regular_size), net(t.net_tangents.data()), net_size(t.net_size),
        at_control_vertex(t.at_control_vertex.data()) {}
  template <int K>
  void tangents(const LimitTable& t, size_t i, Slots<K> last, V<K>& a, V<K>& b) const {
    if (regular[i] >= 0)
      regular_tangents(regular_slots + static_cast<size_t>(regular[i]) * regular_size, regular_size, last, a, b);
    else
      general_tangents(t, i, last, a, b);
  }
  size_t size;
  const int32_t* regular;
  const uint32_t* regular_slots;
  int regular_size;
  const float* net;
  uint32_t net_size;
  const char* at_control_vertex;
};

template <int K, class Slot>
void project_positions(const LimitTable& t, Slots<K> last, bool project, Slot* position) {
  const VertexRule* rule = t.position.data();
  const int32_t* stencil = t.stencil.data();
  const uint32_t *ring = t.ring.data(), *begin = t.stencil_begin.data(), *slot = t.stencil_slot.data();
  const float* weight = t.stencil_w.data();
  for (size_t i = 0, size = t.position.size(); i < size; ++i) {
    if (!project) {
      store(position + i, last[rule[i].centre]);
    } else if (stencil[i] < 0) {
      store(position + i, apply_regular_first(rule[i], ring, last, last));
    } else {  // in the stencil's order, which every fragment shares
      V<K> p{};
      for (uint32_t k = begin[stencil[i]]; k < begin[stencil[i] + 1]; ++k) p = p + last[slot[k]] * weight[k];
      store(position + i, p);
    }
  }
}

typedef int I8 __attribute__((vector_size(32)));

// An 8 x 8 transpose, in three rounds of two-vector shuffles (unpack, shufps, perm2f128 on AVX).
inline void transpose(F8* r) {
  F8 t[8];
  for (int i = 0; i < 8; i += 2) {
    t[i] = __builtin_shuffle(r[i], r[i + 1], I8{0, 8, 1, 9, 4, 12, 5, 13});
    t[i + 1] = __builtin_shuffle(r[i], r[i + 1], I8{2, 10, 3, 11, 6, 14, 7, 15});
  }
  for (int i = 0; i < 8; i += 4)
    for (int j = 0; j < 2; ++j) {
      r[i + 2 * j] = __builtin_shuffle(t[i + j], t[i + j + 2], I8{0, 1, 8, 9, 4, 5, 12, 13});
      r[i + 2 * j + 1] = __builtin_shuffle(t[i + j], t[i + j + 2], I8{2, 3, 10, 11, 6, 7, 14, 15});
    }
  for (int i = 0; i < 4; ++i) {
    t[2 * i] = __builtin_shuffle(r[i], r[i + 4], I8{0, 1, 2, 3, 8, 9, 10, 11});
    t[2 * i + 1] = __builtin_shuffle(r[i], r[i + 4], I8{4, 5, 6, 7, 12, 13, 14, 15});
  }
  for (int i = 0; i < 4; ++i) r[i] = t[2 * i], r[i + 4] = t[2 * i + 1];
}

// Eight entries of eight lanes, x y z each, are 24 rows of lanes; transposed in three blocks of
// eight rows, each column of a block is 8 consecutive floats of one lane's xyz stream.
// `offset`: x y z added to the rows (the origin), or none.
inline void write_chunk(const Lanes<kLanes>* entry, const F8* offset, float* const* out) {
  const F8u* rows = reinterpret_cast<const F8u*>(entry);
  for (int block = 0; block < 3; ++block) {
    F8 r[8];
    for (int i = 0; i < 8; ++i) r[i] = offset ? rows[8 * block + i] + offset[(8 * block + i) % 3] : rows[8 * block + i];
    transpose(r);
    for (int l = 0; l < kLanes; ++l) reinterpret_cast<F8u*>(out[l])[block] = r[l];
  }
}

// m entries into the lanes' xyz streams p (positions, plus `offset`) and n (normals), eight at a
// time through the transposes.
inline void copy_entries(const Lanes<kLanes>* position, const Lanes<kLanes>* normal, uint32_t m, const F8* offset,
                         float** p, float** n) {
  uint32_t i = 0;
  for (; i + 8 <= m; i += 8) {
    write_chunk(position + i, offset, p);
    write_chunk(normal + i, nullptr, n);
    for (int l = 0; l < kLanes; ++l) p[l] += 24, n[l] += 24;
  }
  for (; i < m; ++i) {
    const Lanes<kLanes>&a = position[i], &b = normal[i];
    for (int l = 0; l < kLanes; ++l) {
      p[l][0] = a.x[l] + offset[0][0], p[l][1] = a.y[l] + offset[1][0], p[l][2] = a.z[l] + offset[2][0];
      n[l][0] = b.x[l], n[l][1] = b.y[l], n[l][2] = b.z[l];
      p[l] += 3, n[l] += 3;
    }
  }
}

}  // namespace

// AVX2 where the CPU has it, SSE2 otherwise, every helper inlined into each clone
// (flatten) so that the whole pass runs in the wider lanes. Without fused multiply-adds
// (-ffp-contract=off) and with IEEE min, max, sqrt and division in both, the two give the same
// bits: outputs do not depend on the machine.
#define SDB_KERNEL_CLONES __attribute__((target_clones("avx2", "default"), flatten))

template <class Slot>
SDB_KERNEL_CLONES void refine_level(const LevelTable& t, bool catmark, const Slot* parent, Slot* child) {
  constexpr int K = vectors_of<Slot>;
  const Slots<K> p = slots(parent), opposite = catmark ? slots<Slot>(child) : p;
  Slot* out = child;
  for (const FaceRule& f : t.faces) store(out++, ((p[f.a] + p[f.c]) + (p[f.b] + p[f.d])) * 0.25f);
  for (const EdgeRule& e : t.edges) {
    // A crease or boundary edge has no face term, and its f slots name no point of this level
    // (tables.h): never read them (0 times a stale NaN is NaN on the GPU).
    const V<K> v = (p[e.v0] + p[e.v1]) * e.wv;
    store(out++, e.wf == 0 ? v : v + (opposite[e.f0] + opposite[e.f1]) * e.wf);
  }
  const uint32_t* ring = t.ring.data();
  for (const VertexRule& v : t.vertices) store(out++, apply_regular_first(v, ring, p, opposite));
}

SDB_KERNEL_CLONES void project_to_limit(const LimitTable& t, const Lanes<kLanes>* last, const Lanes<kLanes>* net,
                                        bool project, Lanes<kLanes>* position, Lanes<kLanes>* normal) {
  project_positions(t, slots(last), project, position);
  if (!t.patch_weights.empty()) {
    patch_tangents(t, slots(net), [&](const V<3>& a, const V<3>& b) { unit_normal(a, b, *normal++); });
    return;
  }
  if (t.net_size) return net_normals(t, slots(net), normal);
  const TangentView view(t);
  for (size_t i = 0; i < view.size; ++i) {
    V<3> a, b;
    view.tangents(t, i, slots(last), a, b);
    unit_normal(a, b, normal[i]);
  }
}

SDB_KERNEL_CLONES void project_to_limit(const LimitTable& t, const PairSlot* last, const PairSlot* level0,
                                        const Lanes<1>* net, bool project, Pair* position, Lanes<1>* normal) {
  project_positions(t, slots(last), project, position);
  constexpr int kLocal = 4;  // Pair::local
  if (!t.patch_weights.empty()) {
    patch_tangents(t, slots(level0), [&](const V<1>& a, const V<1>& b) { unit_normal(a, b, kLocal, *normal++); });
    return;
  }
  const TangentView view(t);
  const int h = view.net_size ? kLocal : 0;
  for (size_t i = 0; i < view.size; ++i) {
    if (view.net_size && view.at_control_vertex[i]) {
      net_normal(view.net + i * 2 * view.net_size, view.net_size, net, normal[i]);
      continue;
    }
    V<1> a, b;
    view.tangents(t, i, slots(last), a, b);
    unit_normal(a, b, h, normal[i]);
  }
}

// Through the transposes eight entries at a time: a scalar copy lane by lane was a fifth of the
// kernel's instructions. (Staging a block and streaming it out lane by lane with stores that
// bypass the cache measured 20% slower on the bunny, the same with plain stores.)
SDB_KERNEL_CLONES void write_blocks(const Lanes<kLanes>* position, const Lanes<kLanes>* normal, uint32_t count,
                                    const float* origin, float* const* pos, float* const* nrm) {
  const F8 zero = {}, offset[3] = {zero + origin[0], zero + origin[1], zero + origin[2]};
  float *p[kLanes], *n[kLanes];
  std::copy(pos, pos + kLanes, p), std::copy(nrm, nrm + kLanes, n);
  copy_entries(position, normal, count, offset, p, n);
}

namespace {

void in_bytes(uint32_t& slot) { slot *= kSlotBytes; }
void in_bytes(std::vector<uint32_t>& slots) {
  for (uint32_t& s : slots) in_bytes(s);
}
void in_bytes(VertexRule& r) { in_bytes(r.centre), in_bytes(r.p0), in_bytes(r.p1); }

}  // namespace

void address_in_bytes(ShapeTables& t) {
  if (uint64_t(t.max_slots) * kSlotBytes > std::numeric_limits<uint32_t>::max())
    throw Unsupported("a fragment's level has more slots than 32-bit byte offsets reach");
  for (LevelTable& l : t.levels) {
    for (FaceRule& f : l.faces) in_bytes(f.a), in_bytes(f.b), in_bytes(f.c), in_bytes(f.d);
    for (EdgeRule& e : l.edges) in_bytes(e.v0), in_bytes(e.v1), in_bytes(e.f0), in_bytes(e.f1);
    for (VertexRule& v : l.vertices) in_bytes(v);
    in_bytes(l.ring);
  }
  LimitTable& lim = t.limit;
  for (VertexRule& v : lim.position) in_bytes(v);
  in_bytes(lim.ring), in_bytes(lim.stencil_slot), in_bytes(lim.regular_slots), in_bytes(lim.tangent_slot);
}

template void refine_level<Lanes<kLanes>>(const LevelTable&, bool, const Lanes<kLanes>*, Lanes<kLanes>*);
template void refine_level<PairSlot>(const LevelTable&, bool, const PairSlot*, PairSlot*);

}  // namespace sdb::fragments
