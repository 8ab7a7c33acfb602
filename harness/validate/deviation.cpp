#include "harness/validate/deviation.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "harness/mesh/placement.h"
#include "harness/reference/embree_scene.h"
#include "harness/validate/summary.h"

namespace sdb {
namespace {

// Takes out of `used` the vertices whose coordinate's ptex face `leave` names; returns how many.
template <class Leave>
long leave_out(const Tessellation& t, const LimitEvaluator& ref, std::vector<char>& used, Leave leave) {
  long count = 0;
  for (size_t i = 0; i < used.size(); ++i)
    if (used[i] && t.coords[i].face < uint32_t(ref.num_ptex_faces()) && leave(t.coords[i].face)) used[i] = 0, ++count;
  return count;
}

}  // namespace

DeviationReport measure_deviation(const Tessellation& t, const LimitEvaluator& ref) {
  DeviationReport r;
  const size_t n = t.positions.size();
  r.vertex_pct.assign(n, 0.0f);
  r.vertex_deg.assign(n, 0.0f);
  std::vector<char> used = referenced(t);
  const long no_limit = leave_out(t, ref, used, [&](uint32_t face) { return !ref.has_limit(int(face)); });
  const long no_size = leave_out(t, ref, used, [&](uint32_t face) { return ref.local_size(int(face)) == 0; });
  std::vector<double> dist(n, 0.0), abs_dist(n, 0.0);
  std::vector<char> declared(n, 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 256), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i < range.end(); ++i) {
      if (!used[i]) continue;
      const SurfaceCoord c = t.coords[i];
      const LimitSample s = ref.evaluate(c);
      double d2 = 0, dot = 0, nn = 0;
      for (int k = 0; k < 3; ++k) {
        const double e = double(t.positions[i][k]) - s.position[k];
        d2 += e * e;
        dot += double(t.normals[i][k]) * s.normal[k];
        nn += double(t.normals[i][k]) * t.normals[i][k];
      }
      abs_dist[i] = std::sqrt(d2);
      dist[i] = 100.0 * abs_dist[i] / ref.local_size(static_cast<int>(c.face));
      const double ref_len = std::sqrt(s.normal[0] * s.normal[0] + s.normal[1] * s.normal[1] + s.normal[2] * s.normal[2]);
      const double cosine = nn > 0 ? std::clamp(dot / std::sqrt(nn), -1.0, 1.0) : -1.0;
      r.vertex_pct[i] = static_cast<float>(dist[i]);
      // No reference normal, or none in the output (a scheme's zero normal: it declares it has
      // none there): NaN marks it, and the statistics leave it out and count it.
      r.vertex_deg[i] = ref_len > 0.5 && nn > 0.25 ? static_cast<float>(std::acos(cosine) * 180.0 / M_PI) : NAN;
      if (ref_len > 0.5 && !(nn > 0.25)) declared[i] = 1;
    }
  });
  std::vector<double> pct, deg;
  double max_abs = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!used[i]) continue;
    pct.push_back(dist[i]);
    max_abs = std::max(max_abs, abs_dist[i]);
    if (declared[i]) ++r.normal_declared;
    if (std::isnan(r.vertex_deg[i])) ++r.normal_undefined;
    else deg.push_back(r.vertex_deg[i]);
  }
  const Stats p = stats_of(pct), a = stats_of(deg);
  r.pos_max_pct = p.max, r.pos_mean_pct = p.mean, r.pos_rms_pct = p.rms, r.pos_p95_pct = p.p95;
  r.normal_max_deg = a.max, r.normal_mean_deg = a.mean, r.normal_rms_deg = a.rms, r.normal_p95_deg = a.p95;
  const double diag = used_bounds(ref.mesh()).diagonal();
  r.pos_max_rel_diag = diag > 0 ? max_abs / diag : 0;
  r.vertices = static_cast<long>(pct.size());
  r.no_limit = no_limit, r.no_size = no_size;
  return r;
}

namespace {

// Metro samples a surface at its vertices and at area-weighted random points of its triangles:
// here up to `samples` vertices (all of them when fewer, else a random subset) and `samples`
// points; returns their distances to `target`.
std::vector<double> one_sided(const Tessellation& source, const EmbreeTriangleScene& target, long samples,
                              uint64_t seed, double radius_hint) {
  std::vector<std::array<double, 3>> points;
  const std::vector<char> used = referenced(source);
  std::vector<uint32_t> vertices;
  for (size_t i = 0; i < source.positions.size(); ++i)
    if (used[i]) vertices.push_back(static_cast<uint32_t>(i));
  std::mt19937_64 pick(seed ^ 0x5eedull);
  if (static_cast<long>(vertices.size()) > samples) {
    std::shuffle(vertices.begin(), vertices.end(), pick);
    vertices.resize(static_cast<size_t>(samples));
  }
  for (uint32_t i : vertices) points.push_back({source.positions[i][0], source.positions[i][1], source.positions[i][2]});
  std::vector<double> cumulative;
  double area = 0;
  const auto& P = source.positions;
  for (size_t i = 0; i + 2 < source.triangles.size(); i += 3) {
    const auto &a = P[source.triangles[i]], &b = P[source.triangles[i + 1]], &c = P[source.triangles[i + 2]];
    const double u[3] = {double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
    const double v[3] = {double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
    const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
    area += 0.5 * std::sqrt(x * x + y * y + z * z);
    cumulative.push_back(area);
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (long s = 0; s < samples && area > 0; ++s) {
    const size_t tri = std::lower_bound(cumulative.begin(), cumulative.end(), U(rng) * area) - cumulative.begin();
    double r1 = U(rng), r2 = U(rng);
    if (r1 + r2 > 1) r1 = 1 - r1, r2 = 1 - r2;
    const size_t i = 3 * std::min(tri, cumulative.size() - 1);
    const auto &a = P[source.triangles[i]], &b = P[source.triangles[i + 1]], &c = P[source.triangles[i + 2]];
    points.push_back({a[0] + r1 * (double(b[0]) - a[0]) + r2 * (double(c[0]) - a[0]),
                      a[1] + r1 * (double(b[1]) - a[1]) + r2 * (double(c[1]) - a[1]),
                      a[2] + r1 * (double(b[2]) - a[2]) + r2 * (double(c[2]) - a[2])});
  }
  std::vector<double> d(points.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 512), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) d[i] = target.closest_distance(points[i].data(), radius_hint);
  });
  return d;
}

}  // namespace

HausdorffReport hausdorff(const Tessellation& output, const Tessellation& reference) {
  if (output.triangles.empty() || reference.triangles.empty()) return {};
  return hausdorff(output, reference, EmbreeTriangleScene(reference.positions, reference.triangles));
}

HausdorffReport hausdorff(const Tessellation& output, const Tessellation& reference, const EmbreeTriangleScene& ref_scene) {
  HausdorffReport h;
  const double diag = bounds_of(reference.positions).diagonal();
  if (diag <= 0 || output.triangles.empty() || reference.triangles.empty()) return h;
  const EmbreeTriangleScene out_scene(output.positions, output.triangles);
  const long samples = 50000;  // per direction: as many vertices, as many area-weighted points
  const double hint = 1e-2 * diag;  // the surfaces compared lie close together
  const Stats f = stats_of(one_sided(output, ref_scene, samples, 1, hint));
  const Stats b = stats_of(one_sided(reference, out_scene, samples, 2, hint));
  h.forward_mean = f.mean / diag, h.forward_rms = f.rms / diag, h.forward_max = f.max / diag;
  h.backward_mean = b.mean / diag, h.backward_rms = b.rms / diag, h.backward_max = b.max / diag;
  h.samples = 4 * samples;
  return h;
}

}  // namespace sdb
