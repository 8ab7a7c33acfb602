// What prepare() makes for every backend: the halfedge hierarchy to the depth, the rules' weight
// tables, the limit plan of the last level, and the output's triangles and SurfaceCoords.
#pragma once

#include <memory>
#include <string>

#include "harness/core/scheme.h"
#include "harness/refined/limit.h"
#include "schemes/halfedge/rules.h"
#include "schemes/halfedge/topology.h"

namespace sdb::halfedge {

struct Surface {
  Surface(const ControlMesh& mesh, SubdivisionRule rule, int depth, bool project_to_limit);

  SubdivisionRule rule;
  int depth;
  bool project;
  Hierarchy hierarchy;
  SmoothWeights weights;
  refined::LimitPlan limit;  // empty without projection
  int early = -1;            // the level whose points the plan's early table reads (-1: none)
  float origin[3];           // the control box's centre: levels are refined relative to it (float keeps its precision)
  Tessellation out;          // triangles and coords; positions and normals sized
  // The last level: its counts and sharpness (its halfedges are freed once the output is laid out).
  const Level& last() const { return hierarchy.levels.back(); }
};

// Throws Unsupported where the request's levels would not fit 32-bit indices or this machine's
// memory (`bytes_per_vertex_on_device`: a GPU backend's own buffers, 0 for the CPU).
void check_size(const ControlMesh& mesh, SubdivisionRule rule, int depth);

// cpu and cpu-mt (TBB, `threads` 0: TBB's default): each level's passes as parallel loops.
std::unique_ptr<Evaluation> make_cpu_evaluation(const ControlMesh& mesh, SubdivisionRule rule, int depth,
                                                bool multithreaded, int threads, bool project_to_limit);

}  // namespace sdb::halfedge
