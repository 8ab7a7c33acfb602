// LimitProjector: the closest point of a limit surface to any point in space, for outputs whose
// vertices have no SurfaceCoord on that surface's mesh (a geometry image fitted to the input, a
// refined control mesh): their deviation is their distance from the surface.
//
// An Embree scene of every ptex face tessellated on its own (not shared: each triangle lies in one
// ptex face, so its corners' coords are that face's) finds the face and a start, and Gauss-Newton
// steps on the LimitEvaluator's position and derivatives, kept inside the face's domain, find the
// foot point on the limit surface itself, not on the tessellation's chords. The distance returned
// is to a point of the limit surface: never less than the true distance, and equal to it wherever
// the foot is the local minimum the steps converge to.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "harness/core/tessellation.h"
#include "harness/reference/embree_scene.h"
#include "harness/reference/limit_evaluator.h"

namespace sdb {

class LimitProjector {
 public:
  // Keeps a reference to `limit`, which must outlive it.
  explicit LimitProjector(const LimitEvaluator& limit);
  ~LimitProjector();
  LimitProjector(const LimitProjector&) = delete;
  LimitProjector& operator=(const LimitProjector&) = delete;

  struct Foot {
    SurfaceCoord coord;  // where on the limit surface
    LimitSample limit;   // the surface there
    double distance = 0;
  };
  // Thread-safe. `radius_hint`: where the search starts (nearby surfaces answer fast).
  Foot closest(const Point3d& p, double radius_hint) const;

  const LimitEvaluator& limit() const { return limit_; }
  double diagonal() const { return diagonal_; }

 private:
  const LimitEvaluator& limit_;
  double diagonal_ = 0;
  std::vector<Point3> positions_;
  std::vector<uint32_t> triangles_;
  std::vector<SurfaceCoord> coords_;       // per tessellation vertex
  std::unique_ptr<EmbreeTriangleScene> scene_;
};

}  // namespace sdb
