// vulkan: the same pattern tables (device_tables.h) applied by table-driven compute passes
// (shaders/; pass_plan.h: which, over which entries). A work group is a batch of up to 64
// fragments of one shape, one per invocation, their slots in scratch buffers with the lanes innermost (the
// CPU kernel's layout). Passes: upload, gather (level 0), level 1 .. d, limit (writes the output);
// each timed by timestamps. Fragments run in waves that bound the scratch memory and keep each
// wave's output within one storage binding (128 MiB on lavapipe); a wave's output is contiguous
// because blocks follow the batches' order (surface.h).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "harness/core/scheme.h"

namespace sdb::fragments {

struct FragmentStats;

struct VulkanOptions {
  // Tests: a cap on a wave's scratch and output bindings below the device's, to run many waves.
  uint64_t max_wave_bytes = 0;
  // The poster's Table 1: every frame also draws the output into an offscreen target of this
  // size (a "render" pass, timed), straight from the device buffers. 0: no drawing.
  uint32_t render_width = 0, render_height = 0;
};

// Why there is no Vulkan device to run on, or nullopt.
std::optional<std::string> vulkan_unavailable();

// Throws Unsupported where the device's limits or memory do not take the request (the reason
// names the device and the number).
std::unique_ptr<Evaluation> make_vulkan_evaluation(const ControlMesh& mesh, SubdivisionRule rule, int depth,
                                                   bool project_to_limit, VulkanOptions options = {});

// What a vulkan evaluation built (with its number of waves), or nullopt for another evaluation.
std::optional<FragmentStats> vulkan_stats(const Evaluation& evaluation);

}  // namespace sdb::fragments
