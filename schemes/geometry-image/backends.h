// The scheme's backends behind GeometryImageScheme (scheme.cpp). Each makes the Evaluation of an
// image's closed mesh g0 at one depth: the CPU's Subdivider (cpu.cpp) or the VulkanSubdivider
// (vulkan.cpp), both with the triangles and SurfaceCoords of the opened grid built up front.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "harness/core/scheme.h"
#include "schemes/geometry-image/subdivision.h"

namespace sdb::gim {

struct EvaluationInput {
  std::shared_ptr<const ControlMesh> g0;  // the image's closed mesh; the output's reference
  int base_size = 0;                      // n0
  RunRequest request;
  PassPlan plan = PassPlan::Fused;
};

// cpu (one thread) and cpu-mt (TBB's threads).
std::unique_ptr<Evaluation> make_cpu_evaluation(const EvaluationInput& input);

// vulkan, on gpu::shared_context(). Throws Unsupported (naming `mesh_name`) when the device
// cannot hold the request, gpu::Unavailable without a device.
std::unique_ptr<Evaluation> make_vulkan_evaluation(const EvaluationInput& input, const std::string& mesh_name);

// Why the vulkan backend cannot run here (no loader, no device), or nullopt. Probes once.
std::optional<std::string> vulkan_unavailable();

}  // namespace sdb::gim
