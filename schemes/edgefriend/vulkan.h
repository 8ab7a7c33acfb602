// vulkan: the first step's stencils and each level's kernel as compute shaders (one dispatch a
// level, the paper's form), the limit projection (harness/refined), every pass timed.
#pragma once

#include <memory>

#include "harness/core/scheme.h"

namespace sdb::edgefriend {

// Throws Unsupported where the device's limits or memory do not take the request.
std::unique_ptr<Evaluation> make_vulkan_evaluation(const ControlMesh& mesh, int depth, bool project_to_limit);

}  // namespace sdb::edgefriend
