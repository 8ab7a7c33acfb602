// The float triple the peers' point rules and the limit projection sum in: a sum of products in
// the order written, no fused multiply-add (-ffp-contract=off), as the shaders' `precise` vec3s.
#pragma once

#include <cstddef>
#include <cstdint>

#include "harness/core/tessellation.h"

namespace sdb::refined {

struct P3 {
  float x, y, z;
};
inline P3 operator+(P3 a, P3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline P3 operator-(P3 a, P3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline P3 operator*(P3 a, float w) { return {a.x * w, a.y * w, a.z * w}; }
// Point i of a level's Point3 array; of a float array `stride` floats a point.
inline P3 at(const Point3* p, uint32_t i) { return {p[i][0], p[i][1], p[i][2]}; }
inline P3 load(const float* points, uint32_t stride, uint32_t v) {
  const float* p = points + size_t(v) * stride;
  return {p[0], p[1], p[2]};
}

}  // namespace sdb::refined
