// Unit normal from two tangents, in float as the GPU would.
#pragma once

#include <cmath>

#include "harness/core/control_mesh.h"

namespace sdb {

inline Point3 unit_cross(const float a[3], const float b[3]) {
  const float n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  const float inv = len > 0 ? 1.0f / len : 0.0f;
  return {n[0] * inv, n[1] * inv, n[2] * inv};
}

}  // namespace sdb
