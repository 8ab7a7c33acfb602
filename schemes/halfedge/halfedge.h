// halfedge-cc and halfedge-loop: Dupuy and Vanhoey's halfedge refinement rules (README.md).
#pragma once

#include <memory>

#include "harness/core/scheme.h"

namespace sdb::halfedge {

// The scheme's evaluation of a request (cpu, cpu-mt or vulkan); without `project_to_limit` the
// output is the refined level itself (the tests' comparison with Far's refinement). Throws
// Unsupported past 32-bit indices, this machine's memory or the device's.
std::unique_ptr<Evaluation> make_evaluation(const ControlMesh& mesh, SubdivisionRule rule, const RunRequest& request,
                                            bool project_to_limit);

}  // namespace sdb::halfedge
