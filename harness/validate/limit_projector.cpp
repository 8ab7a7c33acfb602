#include "harness/validate/limit_projector.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sdb {

namespace {

// Segments per ptex-face side: about a million triangles in all (the foot is found by the steps,
// the tessellation only has to pick its face), 2 to 32.
int segments_for(int ptex_faces, bool loop) {
  const double per_face = 1e6 / std::max(1, ptex_faces);
  return std::clamp(static_cast<int>(std::sqrt(loop ? per_face : per_face / 2)), 2, 32);
}

// The grid of one ptex face: a square of (s + 1)^2 points (Catmull-Clark), or the triangle
// u + v <= 1 (Loop); its triangles appended with indices from `base`.
void tessellate_face(uint32_t face, int s, bool loop, std::vector<SurfaceCoord>& coords, std::vector<uint32_t>& tris) {
  const uint32_t base = static_cast<uint32_t>(coords.size());
  std::vector<uint32_t> row_start(s + 2, 0);
  for (int j = 0; j <= s; ++j) {
    row_start[j] = static_cast<uint32_t>(coords.size()) - base;
    for (int i = 0; i <= (loop ? s - j : s); ++i) coords.push_back({face, float(i) / s, float(j) / s});
  }
  auto at = [&](int i, int j) { return base + row_start[j] + static_cast<uint32_t>(i); };
  for (int j = 0; j < s; ++j)
    for (int i = 0; i < (loop ? s - j : s); ++i) {
      tris.insert(tris.end(), {at(i, j), at(i + 1, j), at(i, j + 1)});
      if (!loop || i + j + 1 < s) tris.insert(tris.end(), {at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
    }
}

// (u, v) kept inside the ptex face's domain: the unit square, or the triangle u + v <= 1 for Loop.
void keep_inside(double& u, double& v, bool loop) {
  u = std::clamp(u, 0.0, 1.0), v = std::clamp(v, 0.0, 1.0);
  if (loop && u + v > 1) {
    const double excess = 0.5 * (u + v - 1);
    u = std::max(0.0, u - excess), v = std::max(0.0, v - excess);
    if (u + v > 1) u = 1 - v;
  }
}

double distance2(const Point3d& a, const Point3d& b) {
  const double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
  return x * x + y * y + z * z;
}

double dot(const Point3d& a, const Point3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace

LimitProjector::LimitProjector(const LimitEvaluator& limit) : limit_(limit) {
  diagonal_ = bounds_of(limit.mesh().positions).diagonal();
  const bool loop = limit.rule() == SubdivisionRule::Loop;
  const int faces = limit.num_ptex_faces();
  const int s = segments_for(faces, loop);
  for (int f = 0; f < faces; ++f)
    if (limit.has_limit(f)) tessellate_face(static_cast<uint32_t>(f), s, loop, coords_, triangles_);
  positions_.resize(coords_.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, coords_.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) {
      const Point3d p = limit_.evaluate(coords_[i]).position;
      positions_[i] = {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])};
    }
  });
  if (!triangles_.empty()) scene_ = std::make_unique<EmbreeTriangleScene>(positions_, triangles_);
}

LimitProjector::~LimitProjector() = default;

LimitProjector::Foot LimitProjector::closest(const Point3d& p, double radius_hint) const {
  Foot foot;
  foot.distance = std::numeric_limits<double>::infinity();
  if (!scene_) return foot;
  const EmbreeTriangleScene::Closest near = scene_->closest(p.data(), radius_hint);
  if (!std::isfinite(near.distance)) return foot;
  // Start where the tessellation's closest point is, in its triangle's ptex face.
  const uint32_t* t = &triangles_[3 * size_t(near.triangle)];
  const SurfaceCoord &a = coords_[t[0]], &b = coords_[t[1]], &c = coords_[t[2]];
  const bool loop = limit_.rule() == SubdivisionRule::Loop;
  double u = a.u + near.b1 * (double(b.u) - a.u) + near.b2 * (double(c.u) - a.u);
  double v = a.v + near.b1 * (double(b.v) - a.v) + near.b2 * (double(c.v) - a.v);
  foot.coord = {a.face, float(u), float(v)};
  foot.limit = limit_.evaluate(foot.coord);
  double best = distance2(foot.limit.position, p);
  // Gauss-Newton on |S(u, v) - p|^2, halving a step that does not get closer.
  for (int iteration = 0; iteration < 24; ++iteration) {
    const LimitSample& s = foot.limit;
    const Point3d r{p[0] - s.position[0], p[1] - s.position[1], p[2] - s.position[2]};
    const double uu = dot(s.du, s.du), uv = dot(s.du, s.dv), vv = dot(s.dv, s.dv);
    const double det = uu * vv - uv * uv;
    if (!(det > 1e-24 * uu * vv)) break;
    const double gu = dot(s.du, r), gv = dot(s.dv, r);
    const double step_u = (vv * gu - uv * gv) / det, step_v = (uu * gv - uv * gu) / det;
    // Converged: a step this small moves the foot by a millionth of the face, and the distance,
    // which is stationary there, by far less.
    if (std::abs(step_u) + std::abs(step_v) < 1e-6) break;
    bool moved = false;
    for (double scale = 1; scale > 1.0 / 256 && !moved; scale *= 0.5) {
      double nu = u + scale * step_u, nv = v + scale * step_v;
      keep_inside(nu, nv, loop);
      const SurfaceCoord coord{a.face, float(nu), float(nv)};
      if (coord.u == foot.coord.u && coord.v == foot.coord.v) break;
      const LimitSample next = limit_.evaluate(coord);
      const double d2 = distance2(next.position, p);
      if (d2 < best) {
        best = d2, u = nu, v = nv, foot.coord = coord, foot.limit = next;
        moved = true;
      }
    }
    if (!moved) break;
  }
  foot.distance = std::sqrt(best);
  return foot;
}

}  // namespace sdb
