#include "schemes/fragments/kernel.h"

#include <algorithm>
#include <cmath>

#include "harness/reference/surface_normal.h"

namespace sdb::fragments {
namespace {

inline Vec3 add(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 scale(Vec3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }

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
  std::sort(v, v + n);
  float s = v[0];
  for (int i = 1; i < n; ++i) s += v[i];
  return s;
}

// The sum of a vertex's ring that two fragments starting the ring at different places get
// bit-identical: opposite pairs for valence 4, 6 and 8 (a rotation permutes the pair sums), a
// sorted sum otherwise.
Vec3 ring_sum(const Vec3* src, const uint32_t* ref, int n) {
  switch (n) {
    case 1:
      return src[ref[0]];
    case 2:
      return add(src[ref[0]], src[ref[1]]);
    case 4:
      return add(add(src[ref[0]], src[ref[2]]), add(src[ref[1]], src[ref[3]]));
    case 6: {
      const Vec3 a = add(src[ref[0]], src[ref[3]]), b = add(src[ref[1]], src[ref[4]]), c = add(src[ref[2]], src[ref[5]]);
      return {sum3_sorted(a.x, b.x, c.x), sum3_sorted(a.y, b.y, c.y), sum3_sorted(a.z, b.z, c.z)};
    }
    case 8: {
      Vec3 q[4];
      for (int i = 0; i < 4; ++i) q[i] = add(src[ref[i]], src[ref[i + 4]]);
      return add(add(q[0], q[2]), add(q[1], q[3]));
    }
    default: {
      float x[1024], y[1024], z[1024];  // tables.cpp refuses longer rings
      for (int i = 0; i < n; ++i) x[i] = src[ref[i]].x, y[i] = src[ref[i]].y, z[i] = src[ref[i]].z;
      return {sorted_sum(x, n), sorted_sum(y, n), sorted_sum(z, n)};
    }
  }
}

inline Vec3 apply(const VertexRule& r, const uint32_t* ring, const Vec3* pv, const Vec3* pf) {
  Vec3 s = scale(pv[r.centre], r.wv);
  if (r.wc != 0) s = add(s, scale(add(pv[r.p0], pv[r.p1]), r.wc));
  if (r.num_e) s = add(s, scale(ring_sum(pv, ring + r.ring, r.num_e), r.we));
  if (r.num_f) s = add(s, scale(ring_sum(pf, ring + r.ring + r.num_e, r.num_f), r.wf));
  return s;
}

// Tangents are differences of nearby points: summed in double, so that the normal keeps float
// precision next to a pole of valence 360, where the points crowd together.
Vec3 normal_at(const LimitTable& t, size_t i, const Vec3* last) {
  double t1[3] = {0, 0, 0}, t2[3] = {0, 0, 0};
  for (uint32_t k = t.tangent_begin[i]; k < t.tangent_begin[i + 1]; ++k) {
    const Vec3 p = last[t.tangent_slot[k]];
    const double a = t.tangent_w1[k], b = t.tangent_w2[k];
    t1[0] += a * p.x, t1[1] += a * p.y, t1[2] += a * p.z;
    t2[0] += b * p.x, t2[1] += b * p.y, t2[2] += b * p.z;
  }
  const float f1[3] = {float(t1[0]), float(t1[1]), float(t1[2])}, f2[3] = {float(t2[0]), float(t2[1]), float(t2[2])};
  const Point3 n = unit_cross(f1, f2);
  return {n[0], n[1], n[2]};
}

}  // namespace

void refine_level(const LevelTable& t, bool catmark, const Vec3* parent, Vec3* child) {
  Vec3* out = child;
  for (const FaceRule& f : t.faces)
    *out++ = scale(add(add(parent[f.a], parent[f.c]), add(parent[f.b], parent[f.d])), 0.25f);
  const Vec3* opposite = catmark ? child : parent;
  for (const EdgeRule& e : t.edges)
    *out++ = add(scale(add(parent[e.v0], parent[e.v1]), e.wv), scale(add(opposite[e.f0], opposite[e.f1]), e.wf));
  const uint32_t* ring = t.ring.data();
  for (const VertexRule& v : t.vertices) *out++ = apply(v, ring, parent, opposite);
}

void project_to_limit(const LimitTable& t, const Vec3* last, Vec3* position, Vec3* normal) {
  for (size_t i = 0; i < t.position.size(); ++i) position[i] = apply(t.position[i], t.ring.data(), last, last);
  for (size_t i = 0; i + 1 < t.tangent_begin.size(); ++i) normal[i] = normal_at(t, i, last);
}

void refined_points(const LimitTable& t, const Vec3* last, Vec3* position, Vec3* normal) {
  for (size_t i = 0; i < t.position.size(); ++i) position[i] = last[t.position[i].centre];
  for (size_t i = 0; i + 1 < t.tangent_begin.size(); ++i) normal[i] = normal_at(t, i, last);
}

}  // namespace sdb::fragments
