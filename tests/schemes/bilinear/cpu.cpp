#include "cpu.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "harness/mesh/osd_topology.h"
#include "harness/reference/limit_evaluator.h"

namespace sdb::bilinear {
namespace {

Point3 to_float(const Point3d& p) { return {float(p[0]), float(p[1]), float(p[2])}; }

Point3 bilerp(const std::array<Point3, 4>& c, float u, float v) {
  Point3 p;
  for (int k = 0; k < 3; ++k) {
    const float bottom = c[0][k] + u * (c[1][k] - c[0][k]), top = c[3][k] + u * (c[2][k] - c[3][k]);
    p[k] = bottom + v * (top - bottom);
  }
  return p;
}

Point3 normalised(Point3 n) {
  const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (len > 0)
    for (float& x : n) x /= len;
  return n;
}

}  // namespace

BilinearEvaluation::BilinearEvaluation(const ControlMesh& quads, int rate, bool multithreaded, int repeat)
    : multithreaded_(multithreaded), repeat_(repeat) {
  const auto refiner = make_refiner(quads, SubdivisionRule::CatmullClark);
  SharedLayout layout = make_shared_layout(*refiner, SubdivisionRule::CatmullClark, rate - 1);
  out_ = std::move(layout.topology);
  owned_ = std::move(layout.owned_by_face);
  // The corners of quad f are ptex face f at (0,0), (1,0), (1,1), (0,1) on an all-quad mesh.
  const LimitEvaluator limit(quads, SubdivisionRule::CatmullClark);
  const float corner_uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int f = 0; f < num_faces(quads); ++f) {
    std::array<Point3, 4> p{}, n{};
    for (int c = 0; c < 4 && limit.has_limit(f); ++c) {
      const LimitSample s = limit.evaluate({uint32_t(f), corner_uv[c][0], corner_uv[c][1]});
      p[c] = to_float(s.position);
      n[c] = to_float(s.normal);
    }
    corner_positions_.push_back(p);
    corner_normals_.push_back(n);
  }
  out_.positions.resize(out_.coords.size());
  out_.normals.resize(out_.coords.size());
}

void BilinearEvaluation::evaluate_face(size_t f) {
  for (const SharedLayout::Owned& o : owned_[f]) {
    out_.positions[o.vertex] = bilerp(corner_positions_[f], o.u, o.v);
    out_.normals[o.vertex] = normalised(bilerp(corner_normals_[f], o.u, o.v));
  }
}

void BilinearEvaluation::execute() {
  for (int r = 0; r < repeat_; ++r) {
    if (multithreaded_)
      tbb::parallel_for(tbb::blocked_range<size_t>(0, owned_.size(), 16), [&](const tbb::blocked_range<size_t>& range) {
        for (size_t f = range.begin(); f < range.end(); ++f) evaluate_face(f);
      });
    else
      for (size_t f = 0; f < owned_.size(); ++f) evaluate_face(f);
  }
}

}  // namespace sdb::bilinear
