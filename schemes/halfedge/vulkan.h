// vulkan: each level's passes as compute shaders over the same halfedge buffers (the papers'
// GLSL form, gathered), the limit projection (harness/refined), every pass timed.
#pragma once

#include <memory>

#include "harness/core/scheme.h"

namespace sdb::halfedge {

// Throws Unsupported where the device's limits or memory do not take the request.
std::unique_ptr<Evaluation> make_vulkan_evaluation(const ControlMesh& mesh, SubdivisionRule rule, int depth,
                                                   bool project_to_limit);

}  // namespace sdb::halfedge
