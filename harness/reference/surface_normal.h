// Unit normal from two tangents, in float as the GPU would, and when two tangents give none.
#pragma once

#include <algorithm>
#include <cmath>

#include "harness/core/control_mesh.h"

namespace sdb {

inline Point3 unit_cross(const float a[3], const float b[3]) {
  const float n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  const float inv = len > 0 ? 1.0f / len : 0.0f;
  return {n[0] * inv, n[1] * inv, n[2] * inv};
}

// du x dv has no direction where the parametrization degenerates (a derivative vanishes, or the
// tangents are nearly parallel): along the fold of a face folded over onto its neighbour
// (catmark_val2_back2back), of a flat closed mesh or of a two-sided pillow, where the surface is
// no regular surface and the normals from its two sheets point opposite ways, and at a boundary
// vertex of one face under edge-only interpolation, where du = -dv (loop_saddle_edgeonly). Below
// 1e-6 of the longer tangent's square the cross product is rounding and approximation residue
// whose direction, up to 180 degrees off, judges nothing. Relative, so the same at every scale.
// The yardstick and the osd-bfr peer both ask this.
template <class Real>
bool tangents_degenerate(const Real du[3], const Real dv[3]) {
  const double a[3] = {double(du[0]), double(du[1]), double(du[2])}, b[3] = {double(dv[0]), double(dv[1]), double(dv[2])};
  const double n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  const double scale = std::max(a[0] * a[0] + a[1] * a[1] + a[2] * a[2], b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  return !(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) > 1e-6 * scale);
}

}  // namespace sdb
