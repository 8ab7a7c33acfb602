// How far an output lies from a limit surface, as rows and pictures report it: at the same
// SurfaceCoord where the output's coords are on that surface's mesh (measure_deviation), else by
// nearest points (LimitProjector), which is what is left to compare when a scheme's vertices have
// no place on the input's mesh (a geometry image fitted to it, OpenMesh's refined control mesh).
#pragma once

#include <vector>

#include "harness/core/tessellation.h"
#include "harness/reference/limit_evaluator.h"
#include "harness/validate/deviation.h"
#include "harness/validate/limit_projector.h"

namespace sdb {

struct LimitDistance {
  // measure_deviation's figures; by nearest points, the % of the local face size is the foot's
  // face's, and the normal angle is against the limit normal at the foot.
  DeviationReport report;
  bool nearest_point = false;
  // Per output vertex, its distance over the limit mesh's bounding-box diagonal (0 for vertices
  // no triangle uses), and the 95th percentile of those distances: the figures an approximating
  // scheme is summarised by ("approximates: max, p95").
  std::vector<float> vertex_rel_diag;
  double pos_p95_rel_diag = 0;
};

// At each vertex's SurfaceCoord; `limit` is built on the mesh the coords refer to.
LimitDistance distance_at_coords(const Tessellation& t, const LimitEvaluator& limit);

// From each vertex to the closest point of the projector's limit surface. Output normals of zero
// length (a scheme that computes none) are left out of the normal figures, like an undefined
// reference normal, and counted in report.normal_undefined.
LimitDistance distance_by_nearest_point(const Tessellation& t, const LimitProjector& projector);

}  // namespace sdb
