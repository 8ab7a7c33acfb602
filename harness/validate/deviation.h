// Deviation of a scheme's output from the reference limit surface at the same SurfaceCoord, and
// two-sided Hausdorff distance between surfaces (Metro's convention).
#pragma once

#include <vector>

#include "harness/core/tessellation.h"
#include "harness/reference/embree_scene.h"
#include "harness/reference/limit_evaluator.h"

namespace sdb {

struct DeviationReport {
  // Distance to the limit point at the same SurfaceCoord, in % of the local base-face size.
  double pos_max_pct = 0, pos_mean_pct = 0, pos_rms_pct = 0, pos_p95_pct = 0;
  // Same distance relative to the reference bounding-box diagonal.
  double pos_max_rel_diag = 0;
  // Angle between output normal and limit normal, in degrees.
  double normal_max_deg = 0, normal_mean_deg = 0, normal_rms_deg = 0, normal_p95_deg = 0;
  long vertices = 0;
  // Vertices where the limit has no normal (the reference says so: a valence-2 vertex, a ring
  // folded flat, harness/reference/README.md); left out of the normal statistics, counted.
  long normal_undefined = 0;
  // Of them, vertices where the limit has a normal and the output none (a zero normal: the scheme
  // declares it has none there, its tangents vanishing on a face folded flat over its neighbour).
  long normal_declared = 0;
  // Vertices left out of every statistic, each for a reason the input gives: on a face with no
  // limit surface (a hole, or a boundary face under `interpolateboundary 0`), or on a face of no
  // size (one that repeats a single vertex) where a deviation relative to it means nothing.
  long no_limit = 0, no_size = 0;
  std::vector<float> vertex_pct, vertex_deg;  // per output vertex, for heat maps
};

// Uses t.reference when set, else `reference`'s mesh; the evaluator must be built on that mesh.
DeviationReport measure_deviation(const Tessellation& t, const LimitEvaluator& reference);

struct HausdorffReport {
  // Relative to the reference bounding-box diagonal. forward: output -> reference; backward:
  // reference -> output. Each direction samples up to 50,000 vertices (a random subset beyond
  // that) and 50,000 area-weighted points of the source surface.
  double forward_mean = 0, forward_rms = 0, forward_max = 0;
  double backward_mean = 0, backward_rms = 0, backward_max = 0;
  double max() const { return forward_max > backward_max ? forward_max : backward_max; }
  long samples = 0;
};

HausdorffReport hausdorff(const Tessellation& output, const Tessellation& reference);
// The same with the reference's Embree scene built once by the caller (it is the costly part).
HausdorffReport hausdorff(const Tessellation& output, const Tessellation& reference,
                          const EmbreeTriangleScene& reference_scene);

}  // namespace sdb
