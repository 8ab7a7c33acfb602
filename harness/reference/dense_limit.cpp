#include "harness/reference/dense_limit.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "harness/mesh/osd_topology.h"
#include "harness/reference/shared_layout.h"

namespace sdb {

int dense_limit_segments(int faces) {
  const int rate = std::clamp(static_cast<int>(std::sqrt(1e6 / std::max(1, faces))) + 1, 3, 33);
  return rate - 1;
}

Tessellation limit_tessellation(const LimitEvaluator& limit, int segments) {
  const auto refiner = make_refiner(limit.mesh(), limit.rule());
  Tessellation t = make_shared_layout(*refiner, limit.rule(), segments).topology;
  const size_t n = t.coords.size();
  t.positions.resize(n);
  t.normals.resize(n);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1024), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) {
      const LimitSample s = limit.evaluate(t.coords[i]);
      for (int k = 0; k < 3; ++k) {
        t.positions[i][k] = static_cast<float>(s.position[k]);
        t.normals[i][k] = static_cast<float>(s.normal[k]);
      }
    }
  });
  return t;
}

DenseLimit dense_limit(const LimitEvaluator& limit) {
  DenseLimit d;
  d.surface = limit_tessellation(limit, dense_limit_segments(num_faces(limit.mesh())));
  d.scene = std::make_unique<EmbreeTriangleScene>(d.surface.positions, d.surface.triangles);
  return d;
}

}  // namespace sdb
