// SurfaceSampler: the input surface seen through its spherical parametrization. A direction on
// the sphere is located in the spherical triangulation by an Embree ray from the centre against
// the chord triangles (the embedding makes them star-shaped about the centre, so the ray meets
// exactly one); its barycentric coordinates there place it on the surface's triangle (and, through
// FaceDomains, in its base face: create.cpp samples the limit surface there).
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

  // Where the direction d (need not be unit) meets the spherical triangulation: the triangle and
  // the barycentric weights of its corners 1 and 2 (corner 0 has 1 - b1 - b2). Thread-safe.
  struct Location {
    int triangle = 0;
    double b1 = 0, b2 = 0;
  };
  Location locate(const Vec3d& d) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sdb::gim
