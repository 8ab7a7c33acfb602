// vulkan: the mesh processor as compute passes (Section 3.1 on the paper's future GPU: random
// reads and writes of storage). Per step: the D-facet visit (a pass per class of target node: the
// stencils of Figure 20 or Loop's, as GLSL, gathering each node's 1-disk through the D-LoD's index
// arrays), the D-edge visit for the fast D-edges (the same stencils across the strip), and the
// mesh shader's masks for the rest (mask_table.h: D-vertices, tagged and boundary D-edges); then
// the limit projection the same way (Figure 21), and an output pass. Each pass is timed.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "harness/core/scheme.h"
#include "schemes/mipgh/adaptive.h"
#include "schemes/mipgh/atlas.h"
#include "schemes/mipgh/mipgh.h"

namespace sdb::mipgh {

// Why there is no Vulkan device to run on, or nullopt.
std::optional<std::string> vulkan_unavailable();

// Throws Unsupported where the device's limits or memory do not take the request.
std::unique_ptr<Evaluation> make_vulkan_evaluation(const ControlMesh& mesh, MeshRule rule, DAtlas atlas,
                                                   int depth, bool project_to_limit, AdaptiveCriterion criterion);

}  // namespace sdb::mipgh
