#include "harness/core/control_mesh.h"

#include <algorithm>
#include <cmath>

namespace sdb {

std::vector<int> face_offsets(const ControlMesh& m) {
  std::vector<int> offsets(m.face_sizes.size() + 1, 0);
  for (size_t f = 0; f < m.face_sizes.size(); ++f) offsets[f + 1] = offsets[f] + m.face_sizes[f];
  return offsets;
}

std::string face_location(const ControlMesh& m, int face) {
  if (face >= 0 && face < static_cast<int>(m.face_lines.size()) && m.face_lines[face] > 0)
    return m.source + ":" + std::to_string(m.face_lines[face]);
  return m.source + " (face " + std::to_string(face) + ")";
}

std::string to_string(BoundaryRule rule) {
  switch (rule) {
    case BoundaryRule::None: return "none";
    case BoundaryRule::EdgeOnly: return "edge-only";
    case BoundaryRule::EdgeAndCorner: return "edge-and-corner";
  }
  return "?";
}

double Bounds::diagonal() const {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) d2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
  return std::sqrt(d2);
}

Bounds bounds_of(const std::vector<Point3>& points) {
  Bounds b;
  if (points.empty()) return b;
  for (int k = 0; k < 3; ++k) b.lo[k] = b.hi[k] = points[0][k];
  for (const auto& p : points)
    for (int k = 0; k < 3; ++k) b.lo[k] = std::min(b.lo[k], double(p[k])), b.hi[k] = std::max(b.hi[k], double(p[k]));
  return b;
}

}  // namespace sdb
