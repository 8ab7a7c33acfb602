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
  float origin[3];           // the control box's centre: levels are refined relative to it (float keeps its precision)
  Tessellation out;          // triangles and coords; positions and normals sized
  // The last level: its counts and sharpness (its halfedges are freed once the output is laid out).
  const Level& last() const { return hierarchy.levels.back(); }
};

// Throws Unsupported where the request's levels would not fit 32-bit indices or this machine's
// memory (`bytes_per_vertex_on_device`: a GPU backend's own buffers, 0 for the CPU).
void check_size(const ControlMesh& mesh, SubdivisionRule rule, int depth);

// The note a row carries where a semi-sharp crease outlasts the depth: Far's limit masks, which
// the projection applies, take the sharpness left as infinite there, so the projected points are
// not on the limit surface (issue 39 part A's rule, projecting from a level deep enough, is where
// this goes once it lands). None where none is left.
std::vector<std::string> semi_sharp_notes(const Surface& s);

// cpu and cpu-mt (TBB, `threads` 0: TBB's default): each level's passes as parallel loops.
std::unique_ptr<Evaluation> make_cpu_evaluation(const ControlMesh& mesh, SubdivisionRule rule, int depth,
                                                bool multithreaded, int threads, bool project_to_limit);

}  // namespace sdb::halfedge
