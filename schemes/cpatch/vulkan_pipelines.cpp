#include "schemes/cpatch/vulkan_pipelines.h"

#include <algorithm>
#include <string>

#include "sdb_scheme_cpatch_shaders.h"

namespace sdb::cpatch {
namespace {

namespace shaders = sdb_scheme_cpatch_shaders;
using gpu::Binding;

std::vector<Binding> storage_bindings(size_t count) { return std::vector<Binding>(count, Binding::StorageBuffer); }

gpu::SpecConstant rate_constant(int rate) { return {0, static_cast<uint32_t>(rate)}; }

// corner.vert's buffers (bindings 0-5) and the patch stages' (6-8), shared by cpatch-1pass and
// cpatch-tess.
std::vector<gpu::BufferRange> corner_stage_ranges(const DeviceMesh& m) {
  return {m.control_points.range(), m.first_slot.range(), m.ring.range(), m.valence_constants.range(),
          m.trig.range(),           m.corners.range(),    m.quad_info.range(), m.corner_weights.range(),
          m.grid.range()};
}
constexpr size_t kCornerStageBindings = 9;

gpu::GraphicsPipelineDesc corner_stage_desc(int rate, GpuMode mode, size_t store_extra) {
  gpu::GraphicsPipelineDesc d;
  d.vertex = shaders::get("corner.vert");
  d.fragment = shaders::get(mode == GpuMode::Render ? "surface.frag" : "unused.frag");
  d.bindings = storage_bindings(kCornerStageBindings);
  if (mode == GpuMode::Render)
    d.bindings.push_back(Binding::UniformBuffer);  // camera
  else
    d.bindings.resize(kCornerStageBindings + store_extra, Binding::StorageBuffer);
  d.push_constant_bytes = sizeof(uint32_t);  // first quad of the draw
  d.constants = {rate_constant(rate)};
  d.cull = gpu::CullMode::None;
  return d;
}

}  // namespace

gpu::ComputePipelineDesc vertices_pass_desc() {
  return {shaders::get("vertices.comp"), storage_bindings(9), sizeof(uint32_t), {}};
}

gpu::ComputePipelineDesc patches_pass_desc() { return {shaders::get("patches.comp"), storage_bindings(9), sizeof(uint32_t), {}}; }

gpu::ComputePipelineDesc evaluate_pass_desc(int rate, bool cpatch, bool border_rows, uint32_t local_size) {
  return {shaders::get("evaluate.comp"),
          {Binding::UniformTexelBuffer, Binding::UniformTexelBuffer, Binding::StorageBuffer,
           Binding::StorageBuffer, Binding::StorageBuffer},
          5 * sizeof(uint32_t),
          {rate_constant(rate), {1, cpatch ? 1u : 0u}, {2, border_rows ? 1u : 0u}, {3, local_size}}};
}

int grids_per_instance(int rate) { return std::max(1, kVerticesPerInstance / (rate * rate)); }

gpu::GraphicsPipelineDesc grid_render_desc(int rate, bool heat_map) {
  gpu::GraphicsPipelineDesc d;
  d.vertex = shaders::get(heat_map ? "grid_heat.vert" : "grid.vert");
  d.fragment = shaders::get(heat_map ? "heat.frag" : "surface.frag");
  d.bindings = {Binding::StorageBuffer, Binding::StorageBuffer, Binding::StorageBuffer, Binding::UniformBuffer};
  if (heat_map) d.bindings.push_back(Binding::StorageBuffer);
  d.push_constant_bytes = sizeof(int32_t);  // number of quads
  d.constants = {rate_constant(rate), {1, static_cast<uint32_t>(grids_per_instance(rate))}};
  d.cull = gpu::CullMode::None;
  return d;
}

std::vector<gpu::BufferRange> vertices_pass_bindings(const DeviceMesh& m) {
  return {m.control_points.range(), m.first_slot.range(),  m.ring.range(),
          m.valence_constants.range(), m.trig.range(),     m.limit_points.range(),
          m.face_points.range(),    m.edge_points.range(), m.tangent_points.range()};
}

std::vector<gpu::BufferRange> patches_pass_bindings(const DeviceMesh& m) {
  return {m.control_points.range(), m.corners.range(),     m.quad_info.range(),
          m.corner_weights.range(), m.limit_points.range(), m.face_points.range(),
          m.edge_points.range(),    m.tangent_points.range(), m.records.range()};
}

std::vector<gpu::BufferRange> evaluate_pass_bindings(const DeviceMesh& m, const DeviceOutput& out, const gpu::Chunk& c,
                                                     const gpu::Buffer& quad_lists) {
  return {m.records.texels(VK_FORMAT_R32G32B32A32_SFLOAT), m.grid.texels(VK_FORMAT_R32G32B32A32_SFLOAT),
          out.positions(c), out.normals(c), quad_lists.range()};
}

std::vector<gpu::BufferRange> grid_render_bindings(const DeviceMesh& m, const gpu::Buffer& camera, const gpu::Buffer* heat) {
  std::vector<gpu::BufferRange> r = {m.records.range(), m.quad_info.range(), m.grid.range(), camera.range()};
  if (heat) r.push_back(heat->range());
  return r;
}

gpu::GraphicsPipelineDesc onepass_desc(int rate, GpuMode mode) {
  gpu::GraphicsPipelineDesc d = corner_stage_desc(rate, mode, 2);
  const std::string name =
      "onepass_n" + std::to_string(rate) + (mode == GpuMode::Render ? "_render.geom" : "_store.geom");
  d.geometry = shaders::get(name);
  d.topology = gpu::Topology::LineListWithAdjacency;
  return d;
}

gpu::GraphicsPipelineDesc tess_desc(int rate, GpuMode mode) {
  gpu::GraphicsPipelineDesc d = corner_stage_desc(rate, mode, 3);
  d.tess_control = shaders::get("patch.tesc");
  d.tess_evaluation = shaders::get(mode == GpuMode::Render ? "patch_render.tese" : "patch_store.tese");
  d.topology = gpu::Topology::PatchList;
  d.patch_control_points = 4;
  return d;
}

std::vector<gpu::BufferRange> graphics_render_bindings(const DeviceMesh& m, const gpu::Buffer& camera) {
  std::vector<gpu::BufferRange> r = corner_stage_ranges(m);
  r.push_back(camera.range());
  return r;
}

std::vector<gpu::BufferRange> graphics_store_bindings(const DeviceMesh& m, const DeviceOutput& out, const gpu::Chunk& c,
                                                      const gpu::Buffer* tess_error) {
  std::vector<gpu::BufferRange> r = corner_stage_ranges(m);
  r.push_back(out.positions(c));
  r.push_back(out.normals(c));
  if (tess_error) r.push_back(tess_error->range());
  return r;
}

}  // namespace sdb::cpatch
