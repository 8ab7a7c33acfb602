// Scalar displacement mapping (Section 5): p^k + d^k n^k, per sample of the level-k grid.
//
// d^k is a one-channel image on the same n_k x n_k grid as p^k, so its parametrization over g0
// is implicit, as in the paper. For the displaced surface to stay closed, samples the cut
// identifies must carry the same d: scalar_image_from_function evaluates a function of the limit
// point (bit-identical there) and symmetrize() copies canonical values over their mirrors. The
// normals are left as they are (the displaced surface's own normals would need d's gradient).
#pragma once

#include <functional>
#include <vector>

#include "harness/core/control_mesh.h"

namespace sdb::gim {

struct ScalarImage {
  int size = 0;              // n, as the grid it displaces
  std::vector<float> values; // row-major
};

// Identified samples take the value of their canonical representative.
void symmetrize(ScalarImage& d);

// d(x, y) = f(p(x, y)) over a grid of limit points.
ScalarImage scalar_image_from_function(int n, const std::vector<Point3>& positions,
                                       const std::function<float(const Point3&)>& f);

// positions[i] += d[i] * normals[i].
void displace(const ScalarImage& d, std::vector<Point3>& positions, const std::vector<Point3>& normals);

}  // namespace sdb::gim
