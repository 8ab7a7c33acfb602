#include "schemes/geometry-image/level_of_detail.h"

#include <cmath>
#include <stdexcept>

#include "schemes/geometry-image/closed_mesh.h"
#include "schemes/geometry-image/subdivision.h"
#include "schemes/geometry-image/tessellation_grid.h"

namespace sdb::gim {

namespace {

Point3 midpoint(const Point3& a, const Point3& b) {
  return {0.5f * (a[0] + b[0]), 0.5f * (a[1] + b[1]), 0.5f * (a[2] + b[2])};
}

Point3 lerp(const Point3& a, const Point3& b, float t) {
  const float s = 1.0f - t;
  return {s * a[0] + t * b[0], s * a[1] + t * b[1], s * a[2] + t * b[2]};
}

Point3 unit(const Point3& p) {
  const float len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  return len > 0 ? Point3{p[0] / len, p[1] / len, p[2] / len} : p;
}

// Linear subdivision of one attribute. Each new value is a commutative pair sum, and the cut's
// half turns map pairs onto pairs, so identified samples stay bit-identical.
std::vector<Point3> subdivide_linearly(const std::vector<Point3>& c, int n) {
  const int m = 2 * n - 1;
  std::vector<Point3> f(static_cast<size_t>(m) * m);
  auto at = [&](int x, int y) -> const Point3& { return c[static_cast<size_t>(y) * n + x]; };
  for (int y = 0; y < m; ++y)
    for (int x = 0; x < m; ++x) {
      const int cx = x / 2, cy = y / 2;
      Point3& out = f[static_cast<size_t>(y) * m + x];
      if (x % 2 == 0 && y % 2 == 0) out = at(cx, cy);
      else if (y % 2 == 0) out = midpoint(at(cx, cy), at(cx + 1, cy));
      else if (x % 2 == 0) out = midpoint(at(cx, cy), at(cx, cy + 1));
      else if (anti_diagonal(cx, cy, n)) out = midpoint(at(cx + 1, cy), at(cx, cy + 1));  // on the diagonal
      else out = midpoint(at(cx, cy), at(cx + 1, cy + 1));
    }
  return f;
}

}  // namespace

LimitGrid subsample(const LimitGrid& fine) {
  if (fine.size < 5 || fine.size % 4 != 1) throw std::invalid_argument("subsampling needs a grid of size 4i + 1, i >= 1");
  LimitGrid c;
  c.size = (fine.size + 1) / 2;
  c.positions.resize(static_cast<size_t>(c.size) * c.size);
  c.normals.resize(c.positions.size());
  for (int y = 0; y < c.size; ++y)
    for (int x = 0; x < c.size; ++x) {
      const size_t from = static_cast<size_t>(2 * y) * fine.size + 2 * x, to = static_cast<size_t>(y) * c.size + x;
      c.positions[to] = fine.positions[from];
      c.normals[to] = fine.normals[from];
    }
  return c;
}

LimitGrid linear_subdivide(const LimitGrid& coarse) {
  LimitGrid f;
  f.size = 2 * coarse.size - 1;
  f.positions = subdivide_linearly(coarse.positions, coarse.size);
  f.normals = subdivide_linearly(coarse.normals, coarse.size);
  return f;
}

LimitGrid blend_levels(const LimitGrid& fine, double alpha) {
  const LimitGrid coarse = linear_subdivide(subsample(fine));
  LimitGrid out;
  out.size = fine.size;
  out.positions.resize(fine.positions.size());
  out.normals.resize(fine.normals.size());
  const float t = static_cast<float>(alpha);
  for (size_t i = 0; i < fine.positions.size(); ++i) {
    out.positions[i] = lerp(coarse.positions[i], fine.positions[i], t);
    out.normals[i] = unit(lerp(coarse.normals[i], fine.normals[i], t));
  }
  return out;
}

int lowest_level(int n) {
  int level = 0;
  for (int m = n; m >= 5 && m % 4 == 1; m = (m + 1) / 2) --level;
  return level;
}

LimitGrid limit_grid(const GeometryImage& image, int k) {
  if (k < lowest_level(image.size)) throw std::invalid_argument("level below what this image subsamples to");
  Subdivider subdivider(image.size, std::max(k, 0), PassPlan::Fused);
  LimitGrid grid;
  grid.size = subdivider.size(std::max(k, 0));
  grid.positions.resize(static_cast<size_t>(grid.size) * grid.size);
  grid.normals.resize(grid.positions.size());
  const ControlMesh g0 = closed_mesh(image, "g0", "");
  subdivider.run(g0.positions.data(), grid.positions.data(), grid.normals.data(), SerialRows());
  for (int level = 0; level > k; --level) grid = subsample(grid);
  return grid;
}

Tessellation continuous_level_of_detail(const GeometryImage& image, double level) {
  const int top = static_cast<int>(std::ceil(level));
  const double alpha = level - (top - 1);  // in (0, 1]
  LimitGrid grid = limit_grid(image, top);
  if (alpha < 1.0) {
    if (top - 1 < lowest_level(image.size)) throw std::invalid_argument("level below what this image subsamples to");
    grid = blend_levels(grid, alpha);
  }
  Tessellation t;
  t.triangles = grid_triangles(grid.size);
  t.coords = grid_coords(image.size, top);
  t.positions = std::move(grid.positions);
  t.normals = std::move(grid.normals);
  t.reference = std::make_shared<const ControlMesh>(closed_mesh(image, "g0", ""));
  return t;
}

}  // namespace sdb::gim
