#include "schemes/cpatch/vulkan.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <span>
#include <stdexcept>

#include "harness/core/errors.h"
#include "harness/gpu/errors.h"
#include "schemes/cpatch/vulkan_pipelines.h"
#include "schemes/cpatch/vulkan_resources.h"

namespace sdb::cpatch {
namespace {

// Matches CameraBlock of buffers.glsl (std140).
struct CameraBlock {
  float mvp[16];
  float view_rows[12];
  float heat_scale[4];
};
static_assert(sizeof(CameraBlock) == 128);

// Looks at the control mesh's bounding box (the surface lies within it) from MeshRenderer's
// oblique direction.
gpu::Camera framing_camera(const ControlMesh& quads, float aspect) {
  Point3 lo = quads.positions.front(), hi = lo;
  for (const Point3& p : quads.positions)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  return gpu::frame_bounds(lo, hi, aspect);
}

CameraBlock camera_block(const gpu::Camera& camera, float heat_scale) {
  const std::array<float, 16> mvp = gpu::multiply(camera.projection, camera.view);
  CameraBlock block{};
  std::copy(mvp.begin(), mvp.end(), block.mvp);
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 4; ++col) block.view_rows[row * 4 + col] = camera.view[col * 4 + row];
  block.heat_scale[0] = heat_scale;
  return block;
}

// The grid triangles of `grids` quads, each as grid_output_topology() lays them out, vertex k of
// grid g numbered g N^2 + k; the 2-pass render draw instances them (grid_body.glsl).
std::vector<uint32_t> grid_indices(int rate, int grids) {
  std::vector<uint32_t> indices;
  for (int g = 0; g < grids; ++g)
    for (int j = 0; j + 1 < rate; ++j)
      for (int i = 0; i + 1 < rate; ++i) {
        const uint32_t a = g * rate * rate + j * rate + i, b = a + 1, c = a + rate + 1, d = a + rate;
        indices.insert(indices.end(), {a, b, c, a, c, d});
      }
  return indices;
}

// Storage buffers one stage of the variant sees (every binding is visible to every stage).
uint32_t storage_bindings_needed(GpuVariant variant, GpuMode mode) {
  switch (variant) {
    case GpuVariant::TwoPass:
      return 9;
    case GpuVariant::OnePass:
      return mode == GpuMode::Evaluate ? 11 : 9;
    case GpuVariant::Tessellation:
      return mode == GpuMode::Evaluate ? 12 : 9;
  }
  return 12;
}

GpuOptions evaluate_options(GpuVariant variant, uint64_t max_chunk_bytes) {
  GpuOptions o;
  o.variant = variant;
  o.mode = GpuMode::Evaluate;
  o.max_chunk_bytes = max_chunk_bytes;
  return o;
}

std::string describe(GpuVariant variant, int rate, int quads) {
  return std::string(scheme_name(variant)) + " at N = " + std::to_string(rate) + " on " + std::to_string(quads) +
         " quads";
}

}  // namespace

const char* scheme_name(GpuVariant variant) {
  switch (variant) {
    case GpuVariant::TwoPass:
      return "cpatch-2pass";
    case GpuVariant::OnePass:
      return "cpatch-1pass";
    case GpuVariant::Tessellation:
      return "cpatch-tess";
  }
  return "cpatch";
}

int onepass_max_rate(const gpu::DeviceLimits& limits) {
  int best = 1;
  for (int n = 2; n <= kOnePassCompiledRate; ++n) {
    const uint64_t vertices = 2ull * n * (n - 1);
    if (vertices <= limits.max_geometry_output_vertices &&
        vertices * kOnePassComponents <= limits.max_geometry_total_output_components)
      best = n;
  }
  return best;
}

std::optional<std::string> vulkan_unsupported(GpuVariant variant, GpuMode mode, int rate) {
  const std::string name = scheme_name(variant);
  if (rate < 2) return "rate N = " + std::to_string(rate) + " is below 2 (N x N samples per quad)";
  std::shared_ptr<gpu::Context> ctx;
  try {
    ctx = gpu::shared_context();
  } catch (const gpu::Unavailable& e) {
    return std::string(e.what());
  }
  const gpu::DeviceFeatures& f = ctx->features();
  const gpu::DeviceLimits& l = ctx->limits();
  const std::string& device = ctx->info().name;
  if (storage_bindings_needed(variant, mode) > l.max_per_stage_storage_buffers)
    return name + " binds " + std::to_string(storage_bindings_needed(variant, mode)) + " storage buffers per stage; " +
           device + " allows " + std::to_string(l.max_per_stage_storage_buffers);
  if (variant == GpuVariant::TwoPass && mode == GpuMode::Evaluate && !f.scalar_block_layout)
    return name + " (evaluate-only) stores vec3 arrays with a 12-byte stride; " + device + " lacks scalarBlockLayout";
  const bool stores = variant != GpuVariant::TwoPass && mode == GpuMode::Evaluate;
  if (stores && !f.vertex_pipeline_stores_and_atomics)
    return name + " (evaluate-only) stores from the " +
           (variant == GpuVariant::OnePass ? "geometry" : "tessellation evaluation") + " stage; " + device +
           " lacks vertexPipelineStoresAndAtomics";
  if (variant == GpuVariant::OnePass) {
    if (!f.geometry_shader) return name + ": " + device + " lacks geometry shaders";
    const int max = onepass_max_rate(l);
    if (rate > max) {
      const uint64_t vertices = 2ull * rate * (rate - 1);
      return name + " at N = " + std::to_string(rate) + " emits " + std::to_string(vertices) +
             " vertices x " + std::to_string(kOnePassComponents) + " components per quad from the geometry shader; " +
             device + " allows " + std::to_string(l.max_geometry_output_vertices) + " vertices and " +
             std::to_string(l.max_geometry_total_output_components) + " components (N <= " + std::to_string(max) + ")";
    }
  }
  if (variant == GpuVariant::Tessellation) {
    if (!f.tessellation_shader) return name + ": " + device + " lacks tessellation shaders";
    if (static_cast<uint32_t>(rate - 1) > l.max_tessellation_generation_level)
      return name + " at N = " + std::to_string(rate) + " needs tessellation level " + std::to_string(rate - 1) + "; " +
             device + " generates up to " + std::to_string(l.max_tessellation_generation_level);
  }
  return std::nullopt;
}

// Everything on the device: buffers, pipelines, descriptor sets, the recorded frame.
struct CpatchVulkan::Device {
  Device(gpu::Context& ctx, const ControlMesh& quads, const CpatchTopology& t, const SampleGrid& grid,
         const GpuOptions& o)
      : mesh(ctx, t, grid, o.variant == GpuVariant::TwoPass), frame_timer(ctx), readback_timer(ctx) {
    if (o.mode == GpuMode::Render)
      make_target_and_camera(ctx, quads, o);
    else
      make_output(ctx, t, grid.rate(), o);
    if (o.variant == GpuVariant::TwoPass)
      make_two_pass(ctx, t, grid.rate(), o);
    else
      make_corner_pipeline(ctx, grid.rate(), o);
  }

  void make_target_and_camera(gpu::Context& ctx, const ControlMesh& quads, const GpuOptions& o) {
    target = std::make_unique<gpu::RenderTarget>(ctx, o.width, o.height);
    const CameraBlock block =
        camera_block(o.camera ? *o.camera : framing_camera(quads, target->aspect()), o.heat_scale);
    camera = gpu::device_buffer_with(ctx, std::span<const CameraBlock>(&block, 1), gpu::BufferUsage::Uniform,
                                     "c-patch camera");
  }

  // Evaluate mode: the output buffers; the graphics variants draw into a 1 x 1 target (a draw needs
  // one; nothing reaches it).
  void make_output(gpu::Context& ctx, const CpatchTopology& t, int rate, const GpuOptions& o) {
    output.emplace(ctx, t.num_quads, rate, kLocalSize, o.max_chunk_bytes);
    if (o.variant != GpuVariant::TwoPass) target = std::make_unique<gpu::RenderTarget>(ctx, 1, 1);
    if (o.variant == GpuVariant::Tessellation) {
      tess_error = gpu::Buffer::device(ctx, sizeof(uint32_t), gpu::BufferUsage::Storage, "c-patch tess coord error");
      tess_error_staging = gpu::Buffer::readback(ctx, sizeof(uint32_t), "c-patch tess coord error (readback)");
    }
  }

  void make_two_pass(gpu::Context& ctx, const CpatchTopology& t, int rate, const GpuOptions& o) {
    vertices = gpu::shared_compute_pipeline(ctx, vertices_pass_desc());
    patches = gpu::shared_compute_pipeline(ctx, patches_pass_desc());
    vertices_set = gpu::DescriptorSet(*vertices, vertices_pass_bindings(mesh));
    patches_set = gpu::DescriptorSet(*patches, patches_pass_bindings(mesh));
    if (o.mode == GpuMode::Evaluate) {
      make_evaluate_pass(ctx, t, rate);
      return;
    }
    const bool heat_map = !o.heat_values.empty();
    if (heat_map) heat = gpu::device_buffer_with(ctx, o.heat_values, gpu::BufferUsage::Storage, "c-patch heat values");
    graphics = std::make_unique<gpu::GraphicsPipeline>(ctx, grid_render_desc(rate, heat_map));
    graphics_set = gpu::DescriptorSet(*graphics, grid_render_bindings(mesh, camera, heat_map ? &heat : nullptr));
    indices = gpu::device_buffer_with(ctx, grid_indices(rate, grids_per_instance(rate)), gpu::BufferUsage::Index,
                                      "c-patch grid indices");
  }

  // Four pipelines (patch kind x interior or border rows) sharing one descriptor set per chunk.
  void make_evaluate_pass(gpu::Context& ctx, const CpatchTopology& t, int rate) {
    evaluate_local_size = gpu::work_group_size(ctx.info(), kLocalSize);
    for (int k = 0; k < 4; ++k)
      evaluate[k] = gpu::shared_compute_pipeline(ctx, evaluate_pass_desc(rate, k & 1, k & 2, evaluate_local_size));
    EvaluateRuns plan = cpatch::evaluate_runs(t, output->plan(), uint64_t(rate) * rate);
    evaluate_runs = std::move(plan.runs);
    quad_lists = gpu::storage_table(ctx, std::move(plan.lists), "c-patch evaluate quad lists");
    for (const gpu::Chunk& c : output->plan().chunks)
      chunk_sets.emplace_back(*evaluate[0], evaluate_pass_bindings(mesh, *output, c, quad_lists));
  }

  // cpatch-1pass and cpatch-tess: one graphics pipeline from corner.vert on.
  void make_corner_pipeline(gpu::Context& ctx, int rate, const GpuOptions& o) {
    graphics = std::make_unique<gpu::GraphicsPipeline>(
        ctx, o.variant == GpuVariant::OnePass ? onepass_desc(rate, o.mode) : tess_desc(rate, o.mode));
    if (o.mode == GpuMode::Render) {
      graphics_set = gpu::DescriptorSet(*graphics, graphics_render_bindings(mesh, camera));
      return;
    }
    for (const gpu::Chunk& c : output->plan().chunks)
      chunk_sets.emplace_back(*graphics, graphics_store_bindings(mesh, *output, c, tess_error ? &tess_error : nullptr));
  }

  DeviceMesh mesh;
  std::optional<DeviceOutput> output;             // evaluate mode
  std::unique_ptr<gpu::RenderTarget> target;      // render mode; 1 x 1 for graphics evaluate mode
  gpu::Buffer camera, heat, indices, tess_error, tess_error_staging, quad_lists;
  // The context's (gpu::shared_compute_pipeline: lavapipe compiles each once).
  std::shared_ptr<const gpu::ComputePipeline> vertices, patches;
  std::shared_ptr<const gpu::ComputePipeline> evaluate[4];  // index: cpatch + 2 border_rows
  uint32_t evaluate_local_size = kLocalSize;
  std::vector<EvaluateRun> evaluate_runs;
  std::unique_ptr<gpu::GraphicsPipeline> graphics;
  gpu::DescriptorSet vertices_set, patches_set, graphics_set;
  std::vector<gpu::DescriptorSet> chunk_sets;  // evaluate mode, one per output chunk
  gpu::GpuTimer frame_timer, readback_timer;
  std::optional<gpu::Recording> frame, readback;
};

CpatchVulkan::CpatchVulkan(const ControlMesh& quads, int rate, const GpuOptions& options)
    : ctx_(gpu::shared_context()), topology_(build_topology(quads)), grid_(rate), options_(options) {
  if (auto why = vulkan_unsupported(options.variant, options.mode, rate)) throw gpu::Unsupported(*why);
  const std::string what = describe(options.variant, rate, topology_.num_quads);
  const uint64_t vertices = uint64_t(topology_.num_quads) * grid_.samples();
  if (vertices > std::numeric_limits<uint32_t>::max())
    throw Unsupported(quads.source + ": " + what + " exceeds 2^32 output vertices");
  if (!options.heat_values.empty() &&
      (options.variant != GpuVariant::TwoPass || options.mode != GpuMode::Render || options.heat_values.size() != vertices))
    throw std::invalid_argument("c-patch heat map: 2-pass render mode, one value per output vertex");
  gpu::MemoryNeed need{DeviceMesh::bytes_needed(topology_, grid_, options.variant == GpuVariant::TwoPass), 0};
  if (options.mode == GpuMode::Evaluate) {
    need.device_bytes += 2 * DeviceOutput::array_bytes(topology_.num_quads, rate);
    need.readback_bytes += 2 * DeviceOutput::array_bytes(topology_.num_quads, rate);
  } else {
    need.device_bytes += uint64_t(options.width) * options.height * 8 + options.heat_values.size() * sizeof(float);
  }
  gpu::check_memory(*ctx_, need, what);
  positions_.reserve(quads.positions.size());
  for (const Point3& p : quads.positions) positions_.push_back(to_vec3(p));
  device_ = std::make_unique<Device>(*ctx_, quads, topology_, grid_, options_);
  record_frame();
  if (options_.mode == GpuMode::Evaluate) record_readback();
}

CpatchVulkan::~CpatchVulkan() = default;

void CpatchVulkan::record_frame() {
  Device& d = *device_;
  d.frame = ctx_->record([&](gpu::Commands& cmd) {
    d.frame_timer.reset(cmd);
    d.frame_timer.begin(cmd, gpu::PassKind::Upload, "upload control points");
    d.mesh.record_upload(cmd);
    d.frame_timer.end(cmd);
    if (options_.variant == GpuVariant::TwoPass) {
      record_conversion(cmd);
      record_two_pass_evaluation(cmd);
    } else {
      record_corner_draw(cmd);
    }
  });
}

// cpatch-2pass, pass 1: Table 1 per vertex, then Table 2 per quad streaming out the records.
void CpatchVulkan::record_conversion(gpu::Commands& cmd) {
  Device& d = *device_;
  const gpu::DeviceLimits& limits = ctx_->limits();
  const uint32_t quads = static_cast<uint32_t>(topology_.num_quads);
  d.frame_timer.begin(cmd, gpu::PassKind::Kernel, "pass 1a: Table 1 per vertex");
  cmd.bind(*d.vertices, d.vertices_set);
  cmd.push(static_cast<uint32_t>(topology_.num_vertices));
  cmd.dispatch(gpu::groups_for(topology_.num_vertices, kLocalSize, limits));
  d.frame_timer.end(cmd);
  cmd.barrier(gpu::Stage::Compute, gpu::Stage::Compute);
  d.frame_timer.begin(cmd, gpu::PassKind::Kernel, "pass 1b: Table 2 per quad");
  cmd.bind(*d.patches, d.patches_set);
  cmd.push(quads);
  cmd.dispatch(gpu::groups_for(quads, kLocalSize, limits));
  d.frame_timer.end(cmd);
  cmd.barrier(gpu::Stage::Compute, options_.mode == GpuMode::Render ? gpu::Stage::Vertex : gpu::Stage::Compute);
}

// cpatch-2pass, pass 2: evaluate the records into the output chunks, or draw the instanced grids.
void CpatchVulkan::record_two_pass_evaluation(gpu::Commands& cmd) {
  Device& d = *device_;
  const uint32_t quads = static_cast<uint32_t>(topology_.num_quads);
  if (options_.mode == GpuMode::Render) {
    d.frame_timer.begin(cmd, gpu::PassKind::Draw, "pass 2: evaluate and rasterize");
    d.target->render(cmd, [&](gpu::Commands& c) {
      const uint32_t batch = static_cast<uint32_t>(grids_per_instance(rate()));
      c.bind(*d.graphics, d.graphics_set);
      c.push(static_cast<int32_t>(quads));
      c.bind_index_buffer(d.indices);
      c.draw_indexed(static_cast<uint32_t>(6 * (rate() - 1) * (rate() - 1)) * batch, (quads + batch - 1) / batch);
    });
    d.frame_timer.end(cmd);
    return;
  }
  d.frame_timer.begin(cmd, gpu::PassKind::Kernel, "pass 2: evaluate");
  for (const EvaluateRun& run : d.evaluate_runs)
    for (bool border_rows : {false, true}) record_evaluate_run(cmd, run, border_rows);
  d.frame_timer.end(cmd);
}

// One evaluate.comp dispatch: a run's rows (x: rows 1..N-2, or 0 and N-1) times its quads (y, z).
void CpatchVulkan::record_evaluate_run(gpu::Commands& cmd, const EvaluateRun& run, bool border_rows) const {
  Device& d = *device_;
  const uint32_t last = static_cast<uint32_t>(rate() - 1);
  const uint32_t rows = border_rows ? 2 : last - 1;
  if (rows == 0) return;
  gpu::DeviceLimits quad_dimensions = ctx_->limits();  // the quads take dimensions y and z
  const auto& max = quad_dimensions.max_compute_work_group_count;
  quad_dimensions.max_compute_work_group_count = {max[1], max[2], 1};
  const gpu::Groups groups = gpu::groups_for(run.count, d.evaluate_local_size, quad_dimensions);
  if (groups.z != 1 || rows > max[0])
    throw gpu::Unsupported("c-patch evaluate: " + std::to_string(run.count) + " quads of " + std::to_string(rows) +
                           " rows exceed the device's work group counts");
  const uint32_t push[5] = {run.first_quad, run.list_offset, run.count, border_rows ? 0 : 1u, border_rows ? last : 1u};
  cmd.bind(*d.evaluate[(run.cpatch ? 1 : 0) + (border_rows ? 2 : 0)], d.chunk_sets[run.chunk]);
  cmd.push(push);
  cmd.dispatch(rows, groups.x, groups.y);
}

// cpatch-1pass and cpatch-tess: one draw of the quads' corners (render mode), or one per output
// chunk (evaluate mode, the stages store; nothing is rasterized).
void CpatchVulkan::record_corner_draw(gpu::Commands& cmd) {
  Device& d = *device_;
  const char* stage = options_.variant == GpuVariant::OnePass ? "geometry" : "tessellation";
  if (options_.mode == GpuMode::Render) {
    d.frame_timer.begin(cmd, gpu::PassKind::Draw, std::string("draw: convert, ") + stage + " evaluate, rasterize");
    d.target->render(cmd, [&](gpu::Commands& c) {
      c.bind(*d.graphics, d.graphics_set);
      c.push(uint32_t{0});
      c.draw(4 * static_cast<uint32_t>(topology_.num_quads));
    });
    d.frame_timer.end(cmd);
    return;
  }
  if (d.tess_error) {
    cmd.fill(d.tess_error, 0);
    cmd.barrier(gpu::Stage::Transfer, gpu::Stage::Vertex);
  }
  d.frame_timer.begin(cmd, gpu::PassKind::Kernel, std::string("convert and ") + stage + " evaluate");
  d.target->render(cmd, [&](gpu::Commands& c) {
    const auto& chunks = d.output->plan().chunks;
    for (size_t k = 0; k < chunks.size(); ++k) {
      c.bind(*d.graphics, d.chunk_sets[k]);
      c.push(d.output->first_quad(chunks[k]));
      c.draw(4 * d.output->quads(chunks[k]), 1, 4 * d.output->first_quad(chunks[k]));
    }
  });
  d.frame_timer.end(cmd);
}

void CpatchVulkan::record_readback() {
  Device& d = *device_;
  d.readback = ctx_->record([&](gpu::Commands& cmd) {
    d.readback_timer.reset(cmd);
    d.readback_timer.begin(cmd, gpu::PassKind::Readback, "readback");
    d.output->record_download(cmd);
    if (d.tess_error) cmd.download(d.tess_error, d.tess_error_staging);
    d.readback_timer.end(cmd);
  });
}

void CpatchVulkan::set_camera(const gpu::Camera& camera) {
  if (options_.mode != GpuMode::Render) throw std::logic_error("CpatchVulkan::set_camera: evaluate mode has no camera");
  options_.camera = camera;
  const CameraBlock block = camera_block(camera, options_.heat_scale);
  gpu::upload(*ctx_, device_->camera, &block, sizeof block);
}

void CpatchVulkan::set_positions(const std::vector<Point3>& positions) {
  if (positions.size() != positions_.size()) throw std::invalid_argument("set_positions: vertex count differs");
  for (size_t i = 0; i < positions.size(); ++i) positions_[i] = to_vec3(positions[i]);
}

void CpatchVulkan::execute() {
  device_->mesh.write_positions(positions_);
  ctx_->submit(*device_->frame);
  read_since_execute_ = false;
}

void CpatchVulkan::read_output(Tessellation& out) {
  if (options_.mode != GpuMode::Evaluate) throw std::logic_error("CpatchVulkan::read_output: render mode has no output buffers");
  if (out.positions.size() != uint64_t(topology_.num_quads) * grid_.samples())
    throw std::invalid_argument("CpatchVulkan::read_output: lay `out` out with grid_output_topology()");
  ctx_->submit(*device_->readback);
  device_->output->read(out);
  if (device_->tess_error) {
    uint32_t bits = 0;
    device_->tess_error_staging.read(&bits, sizeof bits);
    std::memcpy(&tess_coord_error_, &bits, sizeof bits);
  }
  read_since_execute_ = true;
}

gpu::Image CpatchVulkan::read_image() {
  if (options_.mode != GpuMode::Render) throw std::logic_error("CpatchVulkan::read_image: evaluate mode renders nothing");
  return device_->target->read(*ctx_);
}

std::optional<GpuTimes> CpatchVulkan::gpu_times() const {
  std::optional<GpuTimes> times = device_->frame_timer.read();
  if (!times || !read_since_execute_) return times;
  if (const std::optional<GpuTimes> readback = device_->readback_timer.read()) {
    times->readback_ms += readback->readback_ms;
    times->passes.insert(times->passes.end(), readback->passes.begin(), readback->passes.end());
  }
  return times;
}

CpatchVulkanEvaluation::CpatchVulkanEvaluation(const ControlMesh& quads, int rate, GpuVariant variant,
                                               uint64_t max_chunk_bytes)
    : gpu_(quads, rate, evaluate_options(variant, max_chunk_bytes)) {
  grid_output_topology(gpu_.topology().num_quads, rate, out_);
}

void CpatchVulkanEvaluation::execute() {
  gpu_.execute();
  read_ = false;
}

const Tessellation& CpatchVulkanEvaluation::result() {
  if (!read_) gpu_.read_output(out_);
  read_ = true;
  return out_;
}

size_t CpatchVulkanEvaluation::bytes_out() const { return 2 * out_.positions.size() * sizeof(Point3); }

}  // namespace sdb::cpatch
