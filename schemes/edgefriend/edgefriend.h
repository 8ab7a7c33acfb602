// edgefriend-cc: Kuth, Oberberger, Chajdas, Meyer, Edge-Friend (HPG 2023) (README.md).
#pragma once

#include <memory>

#include "harness/core/scheme.h"

namespace sdb::edgefriend {

// The scheme's evaluation of a request (cpu, cpu-mt or vulkan); without `project_to_limit` the
// output is the refined level itself (the tests' comparison with Far's refinement). Throws
// Unsupported past 32-bit indices, this machine's memory or the device's; InputError for a mesh
// the structure does not take.
std::unique_ptr<Evaluation> make_evaluation(const ControlMesh& mesh, const RunRequest& request, bool project_to_limit);

}  // namespace sdb::edgefriend
