#include "harness/conformance/limit_judge.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace sdb::conformance {

LimitJudgement judge_against_limit(const Tessellation& t, const LimitEvaluator& limit, double diagonal) {
  std::vector<char> used(t.positions.size(), 0);
  for (uint32_t i : t.triangles) used[i] = 1;
  auto join = [](LimitJudgement a, const LimitJudgement& b) {
    a.max_rel = std::max(a.max_rel, b.max_rel), a.max_deg = std::max(a.max_deg, b.max_deg);
    a.vertices += b.vertices, a.no_normal += b.no_normal, a.no_surface += b.no_surface, a.declared += b.declared;
    return a;
  };
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, t.positions.size(), 256), LimitJudgement{},
      [&](const tbb::blocked_range<size_t>& r, LimitJudgement j) {
        for (size_t i = r.begin(); i < r.end(); ++i) {
          if (!used[i]) continue;
          if (!limit.has_limit(static_cast<int>(t.coords[i].face))) {
            ++j.no_surface;
            continue;
          }
          const LimitSample s = limit.evaluate(t.coords[i]);
          const Point3& p = t.positions[i];
          const double d[3] = {p[0] - s.position[0], p[1] - s.position[1], p[2] - s.position[2]};
          j.max_rel = std::max(j.max_rel, std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / diagonal);
          ++j.vertices;
          const Point3d& n = s.normal;
          if (n[0] * n[0] + n[1] * n[1] + n[2] * n[2] < 0.25) {
            ++j.no_normal;
            continue;
          }
          const Point3& a = t.normals[i];
          if (a[0] * a[0] + a[1] * a[1] + a[2] * a[2] < 0.25f) {
            ++j.declared;
            continue;
          }
          // atan2 of |a x n| and a . n: acos of a dot this close to 1 cannot resolve 0.01 degrees.
          const double c[3] = {a[1] * n[2] - a[2] * n[1], a[2] * n[0] - a[0] * n[2], a[0] * n[1] - a[1] * n[0]};
          const double dot = a[0] * n[0] + a[1] * n[1] + a[2] * n[2];
          j.max_deg = std::max(j.max_deg, std::atan2(std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), dot) * 180 / M_PI);
        }
        return j;
      },
      join);
}

}  // namespace sdb::conformance
