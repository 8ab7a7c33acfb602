// How far two backends' outputs of one request lie apart, node for node: what the Vulkan tests
// of every scheme assert against the cpu's.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "harness/core/tessellation.h"

namespace sdb::conformance {

struct Agreement {
  double max_rel = 0, max_deg = 0;  // largest position gap over `diagonal`; largest normal angle
  size_t identical = 0, vertices = 0;  // positions bit-identical, of all
};

// `a` and `b` lay their output out the same (the caller checks the counts).
inline Agreement agreement(const Tessellation& a, const Tessellation& b, double diagonal) {
  Agreement r;
  r.vertices = a.positions.size();
  for (size_t i = 0; i < a.positions.size(); ++i) {
    const Point3 &p = a.positions[i], &q = b.positions[i];
    r.identical += p == q;
    const double dx = double(p[0]) - q[0], dy = double(p[1]) - q[1], dz = double(p[2]) - q[2];
    r.max_rel = std::max(r.max_rel, std::sqrt(dx * dx + dy * dy + dz * dz) / diagonal);
    if (i >= a.normals.size() || i >= b.normals.size()) continue;
    const Point3 &m = a.normals[i], &n = b.normals[i];
    const double c[3] = {double(m[1]) * n[2] - double(m[2]) * n[1], double(m[2]) * n[0] - double(m[0]) * n[2],
                         double(m[0]) * n[1] - double(m[1]) * n[0]};
    const double dot = double(m[0]) * n[0] + double(m[1]) * n[1] + double(m[2]) * n[2];
    r.max_deg = std::max(r.max_deg, std::atan2(std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), dot) * 180 / M_PI);
  }
  return r;
}

}  // namespace sdb::conformance
