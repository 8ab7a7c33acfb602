// MiPGH, mesh mutation in programmable graphics hardware (Shiue, Goel, Peters 2003): the public
// face of the scheme folder, for its tests and tools. The harness reaches it through the registry
// (scheme.cpp) only.
#pragma once

#include <memory>

#include "harness/core/control_mesh.h"
#include "harness/core/scheme.h"

namespace sdb::mipgh {

// project_to_limit = false returns the last level's refined nodes (the exactness oracle's side,
// and the paper's mutation steps alone: the `limit=0` parameter); the normals are left zero.
std::unique_ptr<Evaluation> make_evaluation(const ControlMesh& mesh, SubdivisionRule rule, const RunRequest& request,
                                            bool project_to_limit = true);

}  // namespace sdb::mipgh
