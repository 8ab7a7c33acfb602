// The pipelines of the c-patch Vulkan variants and the buffers bound to them, in binding order.
// Binding indices match the shaders' BINDING_* defines (shaders/*.comp, *.vert, *_body.glsl).
#pragma once

#include <vector>

#include "harness/gpu/gpu.h"
#include "schemes/cpatch/vulkan.h"
#include "schemes/cpatch/vulkan_resources.h"

namespace sdb::cpatch {

constexpr uint32_t kLocalSize = 64;  // compute invocations per work group (the .comp files)

// cpatch-2pass.
gpu::ComputePipelineDesc vertices_pass_desc();      // pass 1a, Table 1 per vertex
gpu::ComputePipelineDesc patches_pass_desc();       // pass 1b, Table 2 per quad
// Pass 2, evaluate-only (evaluate.comp): one pipeline per patch kind and kind of row.
gpu::ComputePipelineDesc evaluate_pass_desc(int rate, bool cpatch, bool border_rows, uint32_t local_size);
gpu::GraphicsPipelineDesc grid_render_desc(int rate, bool heat_map);  // pass 2, render mode
// Render mode instances batches of this many quad grids (grid_body.glsl): about
// kVerticesPerInstance vertices per instance.
constexpr int kVerticesPerInstance = 1024;
int grids_per_instance(int rate);
std::vector<gpu::BufferRange> vertices_pass_bindings(const DeviceMesh& m);
std::vector<gpu::BufferRange> patches_pass_bindings(const DeviceMesh& m);
std::vector<gpu::BufferRange> evaluate_pass_bindings(const DeviceMesh& m, const DeviceOutput& out, const gpu::Chunk& c,
                                                     const gpu::Buffer& quad_lists);
std::vector<gpu::BufferRange> grid_render_bindings(const DeviceMesh& m, const gpu::Buffer& camera, const gpu::Buffer* heat);

// cpatch-1pass and cpatch-tess: one graphics pipeline each.
gpu::GraphicsPipelineDesc onepass_desc(int rate, GpuMode mode);
gpu::GraphicsPipelineDesc tess_desc(int rate, GpuMode mode);
// Render mode: the corner stages' buffers and the camera.
std::vector<gpu::BufferRange> graphics_render_bindings(const DeviceMesh& m, const gpu::Buffer& camera);
// Evaluate mode: the corner stages' buffers and one chunk of the output (and, for cpatch-tess,
// the tessellation coordinate error).
std::vector<gpu::BufferRange> graphics_store_bindings(const DeviceMesh& m, const DeviceOutput& out, const gpu::Chunk& c,
                                                      const gpu::Buffer* tess_error);

}  // namespace sdb::cpatch
