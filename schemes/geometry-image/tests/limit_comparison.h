// A subdivided image's output against OpenSubdiv's Catmull-Clark limit of g0, split into samples
// away from the cut vertices (where the two surfaces are the same bicubic patch) and near them
// (where Catmull-Clark's valence-2 rules and the paper's patch differ). Shared by the CPU and
// Vulkan surface tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "harness/core/control_mesh.h"
#include "harness/core/tessellation.h"
#include "harness/reference/limit_evaluator.h"
#include "schemes/geometry-image/image.h"

namespace sdb::gim::testing {

inline double diagonal(const std::vector<Point3>& points) { return bounds_of(points).diagonal(); }

// g0 quads whose 2-ring (image positions two steps around the quad, folded by the cut) holds a
// cut vertex.
inline std::vector<char> quads_near_cut_vertices(int n) {
  const CutSymmetry sym(n);
  std::vector<int> cut;
  for (const ImagePos& c : sym.cut_vertices()) cut.push_back(sym.vertex(c.x, c.y));
  std::vector<char> near(static_cast<size_t>(n - 1) * (n - 1), 0);
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i)
      for (int y = j - 2; y <= j + 3; ++y)
        for (int x = i - 2; x <= i + 3; ++x)
          for (int c : cut) near[j * (n - 1) + i] |= sym.vertex(x, y) == c;
  return near;
}

struct LimitComparison {
  double away_max = 0, near_max = 0;  // distance / bounding-box diagonal
  double away_normal_deg = 0, near_normal_deg = 0;
  long away = 0, near = 0;
  long no_reference_normal = 0;
};

// `t` is the output of an n0 x n0 image (t.reference is its g0, t.coords its SurfaceCoords).
inline LimitComparison compare_with_limit(const Tessellation& t, int n0) {
  const LimitEvaluator reference(*t.reference, SubdivisionRule::CatmullClark);
  const std::vector<char> near = quads_near_cut_vertices(n0);
  const double diag = diagonal(t.positions);
  LimitComparison out;
  for (size_t v = 0; v < t.positions.size(); ++v) {
    const LimitSample limit = reference.evaluate(t.coords[v]);
    const Point3& p = t.positions[v];
    const Point3& q = t.normals[v];
    const double d = std::hypot(p[0] - limit.position[0], p[1] - limit.position[1], p[2] - limit.position[2]) / diag;
    // atan2 of |q x n| and q . n: acos of a cosine near 1 would turn the float normal's length
    // error (1e-7) into 0.03 degrees.
    const double* n = limit.normal.data();
    const double cosine = q[0] * n[0] + q[1] * n[1] + q[2] * n[2];
    const double sine = std::hypot(q[1] * n[2] - q[2] * n[1], q[2] * n[0] - q[0] * n[2], q[0] * n[1] - q[1] * n[0]);
    const double degrees = std::atan2(sine, cosine) * 180.0 / M_PI;
    if (n[0] == 0 && n[1] == 0 && n[2] == 0) {
      ++out.no_reference_normal;  // OpenSubdiv's tangents vanish at the valence-2 vertices
      continue;
    }
    if (near[t.coords[v].face]) {
      out.near_max = std::max(out.near_max, d), out.near_normal_deg = std::max(out.near_normal_deg, degrees);
      ++out.near;
    } else {
      out.away_max = std::max(out.away_max, d), out.away_normal_deg = std::max(out.away_normal_deg, degrees);
      ++out.away;
    }
  }
  return out;
}

}  // namespace sdb::gim::testing
