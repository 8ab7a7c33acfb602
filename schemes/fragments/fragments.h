// Mesh fragments with pattern tables (Shiue, Jones, Peters 2005; the Loop poster): the public
// face of the scheme folder, for its tests and tools. The harness reaches the schemes through
// the registry (scheme.cpp) only.
#pragma once

#include <cstddef>
#include <memory>

#include "harness/core/control_mesh.h"
#include "harness/core/scheme.h"

namespace sdb::fragments {

// What prepare built for a mesh and depth, for notes and tests.
struct FragmentStats {
  int fragments = 0, vertex_patches = 0, facet_patches = 0, shapes = 0;
  size_t table_bytes = 0;  // pattern tables of every shape, all levels and the limit
  int waves = 0;           // vulkan: the passes ran this many times, each on a part of the fragments
};

// project_to_limit = false returns the last level's refined points (the exactness oracle's
// side); normals stay the limit normals.
std::unique_ptr<Evaluation> make_evaluation(const ControlMesh& mesh, SubdivisionRule rule, const RunRequest& request,
                                            bool project_to_limit = true);
FragmentStats stats_of(const Evaluation& evaluation);

}  // namespace sdb::fragments
