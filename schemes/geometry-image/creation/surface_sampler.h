// SurfaceSampler: the input surface seen through its spherical parametrization. A direction on
// the sphere is located in the spherical triangulation by an Embree ray from the centre against
// the chord triangles (the embedding makes them star-shaped about the centre, so the ray meets
// exactly one), and its barycentric coordinates there give the surface point.
#pragma once

#include <memory>
#include <vector>

#include "schemes/geometry-image/creation/triangle_mesh.h"

namespace sdb::gim {

class SurfaceSampler {
 public:
  SurfaceSampler(const TriangleMesh& mesh, const std::vector<Vec3d>& sphere);
  ~SurfaceSampler();
  SurfaceSampler(const SurfaceSampler&) = delete;
  SurfaceSampler& operator=(const SurfaceSampler&) = delete;

  // The surface point whose spherical image is the direction d (need not be unit). Thread-safe.
  Vec3d at_direction(const Vec3d& d) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sdb::gim
