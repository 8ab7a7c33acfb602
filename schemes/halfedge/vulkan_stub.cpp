#include "harness/core/errors.h"
#include "schemes/halfedge/vulkan.h"
namespace sdb::halfedge {
std::optional<std::string> vulkan_unavailable() { return "halfedge: the Vulkan path is not built yet"; }
std::unique_ptr<Evaluation> make_vulkan_evaluation(const ControlMesh&, SubdivisionRule, int, bool) { throw Unsupported("halfedge: the Vulkan path is not built yet"); }
}
