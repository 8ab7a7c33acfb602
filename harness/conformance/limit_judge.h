// Every output vertex against the yardstick (harness/reference) at its SurfaceCoord: what the
// recursive schemes' corpus sweeps assert. No sampling and no skipped shape or point: the one
// exclusion is a normal where the limit has none (the yardstick says so), counted.
#pragma once

#include <cstddef>

#include "harness/core/tessellation.h"
#include "harness/reference/limit_evaluator.h"

namespace sdb::conformance {

struct LimitJudgement {
  double max_rel = 0;  // largest distance to the limit over the diagonal
  double max_deg = 0;  // largest angle to the limit's normal on the vertex's face's side
  size_t vertices = 0, no_normal = 0;  // judged; of them where the limit has no normal
  size_t declared = 0;  // of the others, where the output's normal is zero (the scheme gives none)
  // Vertices on a face with no limit surface (a hole's border under the boundary rule "none"),
  // where the scheme draws and the limit has nothing: counted, not judged (issue 45 decides).
  size_t no_surface = 0;
};

// The vertices used by a triangle (the others lie in holes, with no surface).
LimitJudgement judge_against_limit(const Tessellation& t, const LimitEvaluator& limit, double diagonal);

}  // namespace sdb::conformance
