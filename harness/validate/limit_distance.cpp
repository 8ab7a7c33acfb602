#include "harness/validate/limit_distance.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "harness/validate/summary.h"

namespace sdb {

namespace {

double p95_of(const std::vector<float>& per_vertex, const std::vector<char>& used) {
  std::vector<double> d;
  for (size_t i = 0; i < per_vertex.size(); ++i)
    if (used[i]) d.push_back(per_vertex[i]);
  return stats_of(std::move(d)).p95;
}

}  // namespace

LimitDistance distance_at_coords(const Tessellation& t, const LimitEvaluator& limit) {
  LimitDistance out;
  out.report = measure_deviation(t, limit);
  const double diagonal = bounds_of(limit.mesh().positions).diagonal();
  out.vertex_rel_diag.assign(t.positions.size(), 0.0f);
  if (!(diagonal > 0)) return out;
  const std::vector<char> used = referenced(t);
  for (size_t i = 0; i < t.positions.size(); ++i)
    if (used[i])
      out.vertex_rel_diag[i] =
          float(out.report.vertex_pct[i] / 100.0 * limit.local_size(int(t.coords[i].face)) / diagonal);
  out.pos_p95_rel_diag = p95_of(out.vertex_rel_diag, used);
  return out;
}

LimitDistance distance_by_nearest_point(const Tessellation& t, const LimitProjector& projector) {
  LimitDistance out;
  out.nearest_point = true;
  DeviationReport& r = out.report;
  const size_t n = t.positions.size();
  const double diagonal = projector.diagonal();
  r.vertex_pct.assign(n, 0.0f);
  r.vertex_deg.assign(n, 0.0f);
  out.vertex_rel_diag.assign(n, 0.0f);
  const std::vector<char> used = referenced(t);
  std::vector<double> distance(n, 0.0);
  // The outputs compared lie close to the surface: the search starts within 2% of the diagonal.
  const double hint = 0.02 * diagonal;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 256), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i < range.end(); ++i) {
      if (!used[i]) continue;
      const Point3& q = t.positions[i];
      const LimitProjector::Foot foot = projector.closest({q[0], q[1], q[2]}, hint);
      distance[i] = foot.distance;
      r.vertex_pct[i] = float(100.0 * foot.distance / projector.limit().local_size(int(foot.coord.face)));
      out.vertex_rel_diag[i] = diagonal > 0 ? float(foot.distance / diagonal) : 0.0f;
      const Point3& m = t.normals.size() == n ? t.normals[i] : Point3{0, 0, 0};
      const Point3d& l = foot.limit.normal;
      const double mm = double(m[0]) * m[0] + double(m[1]) * m[1] + double(m[2]) * m[2];
      const double ll = l[0] * l[0] + l[1] * l[1] + l[2] * l[2];
      const double dot = m[0] * l[0] + m[1] * l[1] + m[2] * l[2];
      // No output normal or no limit normal there: NaN marks it, and the statistics leave it out.
      r.vertex_deg[i] = mm > 0 && ll > 0.25
                            ? float(std::acos(std::clamp(dot / std::sqrt(mm * ll), -1.0, 1.0)) * 180.0 / M_PI)
                            : NAN;
    }
  });
  std::vector<double> pct, deg;
  double max_abs = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!used[i]) continue;
    pct.push_back(r.vertex_pct[i]);
    max_abs = std::max(max_abs, distance[i]);
    if (std::isnan(r.vertex_deg[i])) ++r.normal_undefined;
    else deg.push_back(r.vertex_deg[i]);
  }
  const Stats p = stats_of(pct), a = stats_of(deg);
  r.pos_max_pct = p.max, r.pos_mean_pct = p.mean, r.pos_rms_pct = p.rms, r.pos_p95_pct = p.p95;
  r.normal_max_deg = a.max, r.normal_mean_deg = a.mean, r.normal_rms_deg = a.rms, r.normal_p95_deg = a.p95;
  r.pos_max_rel_diag = diagonal > 0 ? max_abs / diagonal : 0;
  r.vertices = static_cast<long>(pct.size());
  out.pos_p95_rel_diag = p95_of(out.vertex_rel_diag, used);
  return out;
}

}  // namespace sdb
