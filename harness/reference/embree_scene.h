// Small RAII layer over Embree 3: a process-wide device and a static triangle scene that answers
// "every crossing along a line" (for the ray-crack check) and "closest point" (for Hausdorff).
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>
#include <limits>
#include <vector>

#include "harness/core/control_mesh.h"

namespace sdb {

// The process-wide Embree device.
RTCDevice embree_device();
// Throws std::runtime_error with `what` if Embree reported an error on this thread.
void check_embree(const char* what);

// Embree asserts, aborting the process, on a vertex or a ray origin past FLT_LARGE (1.8e18), and
// the ray-crack check starts its lines 2.5 bounding radii out: positions handed to Embree stay
// within this magnitude.
inline constexpr double kEmbreeRange = 1e17;
// How many of `positions` are NaN, infinite or past kEmbreeRange in some coordinate.
long positions_out_of_range(const std::vector<Point3>& positions);

class EmbreeTriangleScene {
 public:
  // positions: xyz per vertex; triangles: three indices each.
  EmbreeTriangleScene(const std::vector<Point3>& positions, const std::vector<uint32_t>& triangles);
  ~EmbreeTriangleScene();
  EmbreeTriangleScene(const EmbreeTriangleScene&) = delete;
  EmbreeTriangleScene& operator=(const EmbreeTriangleScene&) = delete;

  struct LineCrossings {
    int count = 0;
    // A hit closer to a triangle's edge or vertex than its barycentrics can be trusted (at least
    // `edge_eps`, more for grazing lines and far origins): whether the line crosses there,
    // touches a ridge or passes between two triangles is not decidable in float.
    bool ambiguous = false;
  };
  // Every crossing of origin + t * dir for t in [0, tfar]. Thread-safe.
  LineCrossings crossings(const float origin[3], const float dir[3], float tfar, float edge_eps) const;

  // Distance from p to the closest point of the surface. Thread-safe. The search starts within
  // `radius_hint` (nearby surfaces answer fast) and widens to everything when nothing is there.
  double closest_distance(const double p[3], double radius_hint = std::numeric_limits<double>::infinity()) const;
  // The same, with the triangle the closest point lies on (its index in `triangles`) and where:
  // corner 0 + b1 (corner 1 - corner 0) + b2 (corner 2 - corner 0).
  struct Closest {
    double distance = std::numeric_limits<double>::infinity();
    uint32_t triangle = 0;
    double b1 = 0, b2 = 0;
  };
  Closest closest(const double p[3], double radius_hint = std::numeric_limits<double>::infinity()) const;

 private:
  RTCScene scene_ = nullptr;
  std::vector<Point3> positions_;
  std::vector<uint32_t> triangles_;
};

}  // namespace sdb
