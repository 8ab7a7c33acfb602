// What prepare() makes for every backend: OpenSubdiv's level 1 of the mesh (its topology and the
// first step's stencils), the Edge-Friend levels to the depth, the smooth weights, the limit plan
// of the last level, and the output's triangles and SurfaceCoords.
#pragma once

#include <memory>
#include <string>

#include "harness/core/scheme.h"
#include "harness/refined/limit.h"
#include "schemes/edgefriend/first_step.h"
#include "schemes/edgefriend/rules.h"
#include "schemes/edgefriend/topology.h"

namespace sdb::edgefriend {

struct Surface {
  Surface(const ControlMesh& mesh, int depth, bool project_to_limit);

  int depth;
  bool project;
  Hierarchy hierarchy;
  StencilTable stencils;
  SmoothWeights weights;
  refined::LimitPlan limit;  // empty without projection
  int early = -1;            // the level (index into hierarchy.levels) the plan's early table reads; -1: none
  float origin[3];           // the control box's centre: levels are refined relative to it (float keeps its precision)
  Tessellation out;          // triangles and coords; positions and normals sized
  const Level& last() const { return hierarchy.levels.back(); }
  // The output index table of the step that writes the last level (null: none needed).
  const uint32_t* out_index() const { return hierarchy.out_index.empty() ? nullptr : hierarchy.out_index.data(); }
};

// Throws Unsupported where the depth would not fit 32-bit indices or 60% of this machine's memory.
void check_size(const ControlMesh& mesh, int depth);

// cpu and cpu-mt (TBB, `threads` 0: TBB's default).
std::unique_ptr<Evaluation> make_cpu_evaluation(const ControlMesh& mesh, int depth, bool multithreaded, int threads,
                                                bool project_to_limit);

}  // namespace sdb::edgefriend
