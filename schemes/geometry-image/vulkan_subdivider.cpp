#include "schemes/geometry-image/vulkan_subdivider.h"

#include <algorithm>
#include <cstdio>
#include <initializer_list>
#include <numeric>
#include <stdexcept>

#include "sdb_scheme_geometry_image_shaders.h"

namespace sdb::gim {

namespace {

namespace shaders = sdb_scheme_geometry_image_shaders;
using gpu::Binding;
using gpu::BufferUsage;

// Invocations per work group (the shaders' local_size_x_id = 0).
constexpr uint32_t kLocalSize = 64;
static_assert(kLocalSize >= 4, "the cut-vertex pass runs its four invocations in one work group");
// The most storage buffers one pass binds: pad's gather table, control points and destination.
constexpr uint32_t kMaxBindings = 3;

// The shaders' push constants (gim_common.glsl).
struct Push {
  uint32_t src_side = 0, dst_side = 0, first_row = 0, rows = 0;
};

// Work groups for `rows` rows of `width` samples: x along a row, one row of groups per row.
gpu::Groups row_groups(uint64_t width, uint64_t rows) {
  return {static_cast<uint32_t>((width + kLocalSize - 1) / kLocalSize), static_cast<uint32_t>(rows), 1};
}

// Vertices per output-pass invocation (output_grid.glsl).
constexpr uint64_t kOutputGroup = 8;
constexpr uint64_t kOutputGroupBytes = kOutputGroup * sizeof(Point3);
// After the outputs: the grid's last group writes up to seven copies of its last vertex there.
constexpr uint64_t kOutputPadding = kOutputGroupBytes;

// A chunk's outputs as the output passes write them: whole groups of eight vertices (96 bytes),
// into the padding after the last.
gpu::BufferRange output_range(const gpu::Buffer& output, const gpu::Chunk& c) {
  return output.range(c.byte_offset, (c.bytes + kOutputGroupBytes - 1) / kOutputGroupBytes * kOutputGroupBytes);
}

uint64_t image_bytes(int side) { return uint64_t(side) * uint64_t(side) * 4 * sizeof(float); }

double mib(uint64_t bytes) { return double(bytes) / double(1 << 20); }

std::string mib_text(uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", mib(bytes));
  return text;
}

// Padded sides of every image the passes keep: g^0 .. g^k, and L[g^{k-1}] (per-mask plan).
std::vector<int> image_sides(int base_size, int levels, PassPlan plan) {
  std::vector<int> sides;
  for (int k = 0; k <= levels; ++k) sides.push_back(level_size(base_size, k) + 2);
  if (plan == PassPlan::PerMask && levels > 0) sides.push_back(2 * sides[levels - 1] - 1);
  return sides;
}

// The cut-vertex stencils as the shader reads them: six ints per cut vertex.
std::vector<int32_t> stencil_words(const std::array<CutVertexStencil, 4>& stencils) {
  std::vector<int32_t> words;
  for (const CutVertexStencil& s : stencils)
    for (int w : {s.output, s.centre, s.u, s.e, s.ue, s.mu_e}) words.push_back(w);
  return words;
}

// Images are read through vec4 texel views (source_planes.glsl) and written through storage
// buffers, or rgba32f storage texel views past one storage binding (destination_planes.glsl);
// outputs through storage buffers (output_grid.glsl); tables are storage buffers.
constexpr Binding kRead = Binding::UniformTexelBuffer, kTexelWrite = Binding::StorageTexelBuffer,
                  kTable = Binding::StorageBuffer;
const BufferUsage kImageUsage = BufferUsage::UniformTexel | BufferUsage::StorageTexel | BufferUsage::Storage;

gpu::ComputePipelineDesc pass(const char* shader, std::vector<Binding> bindings) {
  return {shaders::get(shader), std::move(bindings), sizeof(Push), {{0, kLocalSize}}};
}

// An output pass (output_grid.glsl): where the n x n grid has n >= 8 a block's eight vertices share
// one fetch window, every block's as if in one row, then (row_ends) the blocks holding a row's end
// with the window that crosses it; smaller grids fetch per vertex.
enum class OutputWindow : uint32_t { PerVertex = 0, Crossing = 1, Row = 2 };  // output_grid.glsl's kWindow

gpu::ComputePipelineDesc output_pass(const char* shader, std::vector<Binding> bindings, uint64_t n, bool row_ends) {
  gpu::ComputePipelineDesc desc = pass(shader, std::move(bindings));
  const OutputWindow window = n < 8 ? OutputWindow::PerVertex : row_ends ? OutputWindow::Crossing : OutputWindow::Row;
  desc.constants.push_back({1, static_cast<uint32_t>(window)});
  desc.constants.push_back({2, row_ends ? 1u : 0u});
  return desc;
}

gpu::BufferRange image_view(const gpu::Buffer& image) { return image.texels(VK_FORMAT_R32G32B32A32_SFLOAT); }


}  // namespace

// The pipelines a plan uses; the others stay empty.
struct VulkanSubdivider::Pipelines {
  // The context's (gpu::shared_compute_pipeline: lavapipe compiles each once).
  std::shared_ptr<const gpu::ComputePipeline> pad, split, average, split_average, limit, normal, limit_normal, cut_normal;
  // The output passes' second dispatches, the blocks holding a row's end (none where n < 8).
  std::shared_ptr<const gpu::ComputePipeline> limit_ends, normal_ends, limit_normal_ends;
};

std::optional<std::string> VulkanSubdivider::unsupported(const gpu::Context& ctx, int base_size, int levels,
                                                         PassPlan plan) {
  const gpu::DeviceLimits& limits = ctx.limits();
  const std::string& device = ctx.info().name;
  if (limits.max_per_stage_storage_buffers < kMaxBindings)
    return device + " binds " + std::to_string(limits.max_per_stage_storage_buffers) +
           " storage buffers per shader stage; the geometry-image passes bind " + std::to_string(kMaxBindings);
  const std::vector<int> sides = image_sides(base_size, levels, plan);
  const int widest = *std::max_element(sides.begin(), sides.end());
  const uint64_t largest_buffer = std::min(limits.max_memory_allocation_size, limits.max_buffer_size);
  const uint64_t texels = uint64_t(widest) * uint64_t(widest), bytes = image_bytes(widest);
  const std::string image = "a " + std::to_string(base_size) + " x " + std::to_string(base_size) + " image at depth " +
                            std::to_string(levels);
  if (bytes > largest_buffer || texels > UINT32_MAX)
    return image + " needs padded images of " + std::to_string(widest) + " x " + std::to_string(widest) +
           " vec4 (" + mib_text(bytes) + ") in one buffer; " + device + " allocates at most " + mib_text(largest_buffer);
  if (texels > limits.max_texel_buffer_elements)
    return image + " reads padded images of " + std::to_string(widest) + " x " + std::to_string(widest) +
           " texels through texel views; " + device + " allows " + std::to_string(limits.max_texel_buffer_elements) +
           " texels in one";
  const gpu::Groups groups = row_groups(uint64_t(widest), uint64_t(widest));
  if (groups.x > limits.max_compute_work_group_count[0] || groups.y > limits.max_compute_work_group_count[1])
    return image + " dispatches " + std::to_string(groups.x) + " x " + std::to_string(groups.y) +
           " work groups per pass; " + device + " allows " + std::to_string(limits.max_compute_work_group_count[0]) +
           " x " + std::to_string(limits.max_compute_work_group_count[1]);
  const uint64_t n = uint64_t(level_size(base_size, levels));
  const uint64_t output = n * n * sizeof(Point3);
  if (output > largest_buffer)
    return image + " writes " + mib_text(output) + " of positions, more than one buffer of " + device + " holds (" +
           mib_text(largest_buffer) + ")";
  uint64_t total = 2 * output;
  for (int side : sides) total += image_bytes(side);
  if (limits.device_local_bytes > 0 && total > limits.device_local_bytes)
    return image + " needs " + mib_text(total) + " of device memory; " + device + " has " +
           mib_text(limits.device_local_bytes);
  return std::nullopt;
}

VulkanSubdivider::VulkanSubdivider(gpu::Context& ctx, int base_size, int levels, PassPlan plan,
                                   VulkanSubdividerOptions options)
    : ctx_(ctx), base_size_(base_size), levels_(levels), plan_(plan), frame_timer_(ctx), readback_timer_(ctx) {
  if (levels < 0) throw std::invalid_argument("negative subdivision level");
  if (auto why = unsupported(ctx, base_size, levels, plan)) throw gpu::Unsupported(*why);
  const CutSymmetry sym(base_size);
  control_vertices_ = static_cast<size_t>(sym.num_vertices());
  const uint64_t control_bytes = control_vertices_ * sizeof(Point3);
  control_staging_ = gpu::Buffer::upload(ctx, control_bytes, "g0 control points (staging)");
  control_ = gpu::Buffer::device(ctx, control_bytes, BufferUsage::Storage, "g0 control points");
  gather_ = gpu::device_buffer_with(ctx, padding_gather_table(sym), BufferUsage::Storage, "padding gather table");
  cut_stencils_ = cut_vertex_stencils(size(levels));
  stencils_ = gpu::device_buffer_with(ctx, stencil_words(cut_stencils_), BufferUsage::Storage, "cut-vertex stencils");

  for (int k = 0; k <= levels; ++k) images_.push_back(make_image(size(k) + 2, "g^" + std::to_string(k)));
  const std::vector<int> sides = image_sides(base_size, levels, plan);
  const uint64_t binding = options.max_image_binding_bytes ? std::min(options.max_image_binding_bytes, ctx.limits().max_storage_buffer_range)
                                                           : ctx.limits().max_storage_buffer_range;
  texel_destinations_ = image_bytes(*std::max_element(sides.begin(), sides.end())) > binding;
  if (plan == PassPlan::PerMask && levels > 0) split_ = make_image(2 * images_[levels - 1].side - 1, "L[g^k]");

  const uint64_t n = uint64_t(size(levels));
  // Chunks of whole groups of eight rows: a multiple of eight vertices, as an output pass writes
  // them (output_grid.glsl), but in the last chunk, whose binding rounds up to a whole group: one
  // group's bytes are kept free under the binding range for it.
  const uint64_t range_cap = ctx.limits().max_storage_buffer_range - kOutputGroupBytes;
  const uint64_t chunk_cap = options.max_output_chunk_bytes ? std::min(options.max_output_chunk_bytes, range_cap) : range_cap;
  outputs_ = gpu::plan_chunks(ctx.limits(), {n * n, sizeof(Point3), std::lcm(n, kOutputGroup), kLocalSize, chunk_cap});
  if (outputs_.buffer_bytes.size() != 1)
    throw gpu::Unsupported("the positions of a " + std::to_string(n) + " x " + std::to_string(n) +
                           " grid do not fit one buffer of " + ctx.info().name);
  // Padded by a group: the last group of eight of the last chunk writes up to seven vertices there.
  const uint64_t output_bytes = outputs_.buffer_bytes[0] + kOutputPadding;
  const BufferUsage output_usage = BufferUsage::Storage | BufferUsage::Vertex;
  positions_ = gpu::Buffer::device(ctx, output_bytes, output_usage, "p^k positions");
  normals_ = gpu::Buffer::device(ctx, output_bytes, output_usage, "n^k normals");
  positions_staging_ = gpu::Buffer::readback(ctx, output_bytes, "p^k positions (readback)");
  normals_staging_ = gpu::Buffer::readback(ctx, output_bytes, "n^k normals (readback)");

  make_pipelines();
  make_descriptor_sets();
  record_frame();
  record_readback();
}

VulkanSubdivider::~VulkanSubdivider() = default;

VulkanSubdivider::DeviceImage VulkanSubdivider::make_image(int side, const std::string& name) const {
  return {side, gpu::Buffer::device(ctx_, image_bytes(side), kImageUsage, name)};
}

void VulkanSubdivider::make_pipelines() {
  pipelines_ = std::make_unique<Pipelines>();
  Pipelines& p = *pipelines_;
  const uint64_t n = uint64_t(size(levels_));
  // The image passes' destination: a storage buffer, or (the *_texels variants) a texel view.
  const Binding write = texel_destinations_ ? kTexelWrite : kTable;
  auto image_pass = [&](const std::string& name, std::vector<Binding> bindings) {
    return pass((name + (texel_destinations_ ? "_texels.comp" : ".comp")).c_str(), std::move(bindings));
  };
  p.pad = gpu::shared_compute_pipeline(ctx_, image_pass("pad", {kTable, kTable, write}));
  p.cut_normal = gpu::shared_compute_pipeline(ctx_, pass("cut_normal.comp", {kRead, kTable, kTable}));
  // An output pass's pipeline over every block and, where n >= 8, its row-end pipeline.
  using PipelinePtr = std::shared_ptr<const gpu::ComputePipeline>;
  auto output_pipelines = [&](const char* shader, const std::vector<Binding>& bindings, PipelinePtr& every_block,
                              PipelinePtr& row_ends) {
    every_block = gpu::shared_compute_pipeline(ctx_, output_pass(shader, bindings, n, false));
    if (n >= 8) row_ends = gpu::shared_compute_pipeline(ctx_, output_pass(shader, bindings, n, true));
  };
  if (plan_ == PassPlan::Fused) {
    p.split_average = gpu::shared_compute_pipeline(ctx_, image_pass("split_average", {kRead, write}));
    output_pipelines("limit_normal.comp", {kRead, kTable, kTable}, p.limit_normal, p.limit_normal_ends);
  } else {
    p.split = gpu::shared_compute_pipeline(ctx_, image_pass("split", {kRead, write}));
    p.average = gpu::shared_compute_pipeline(ctx_, image_pass("average", {kRead, write}));
    output_pipelines("limit.comp", {kRead, kTable}, p.limit, p.limit_ends);
    output_pipelines("normal.comp", {kRead, kTable}, p.normal, p.normal_ends);
  }
}

gpu::BufferRange VulkanSubdivider::destination(const DeviceImage& image) const {
  return texel_destinations_ ? image_view(image.texels) : image.texels.range();
}

void VulkanSubdivider::make_descriptor_sets() {
  const Pipelines& p = *pipelines_;
  auto image_to_image = [&](const gpu::ComputePipeline& pipeline, const DeviceImage& src, const DeviceImage& dst) {
    return gpu::DescriptorSet(pipeline, {image_view(src.texels), destination(dst)});
  };
  pad_set_ = gpu::DescriptorSet(*p.pad, {gather_.range(), control_.range(), destination(images_[0])});
  for (int k = 0; k < levels_; ++k) {
    if (plan_ == PassPlan::Fused) {
      fused_sets_.push_back(image_to_image(*p.split_average, images_[k], images_[k + 1]));
    } else {
      split_sets_.push_back(image_to_image(*p.split, images_[k], split_));
      average_sets_.push_back(image_to_image(*p.average, split_, images_[k + 1]));
    }
  }
  // Output passes: the last image, then the chunk's part of the outputs.
  const gpu::BufferRange last = image_view(images_[levels_].texels);
  for (const gpu::Chunk& c : outputs_.chunks) {
    const gpu::BufferRange nrm = normals_.range(c.byte_offset, c.bytes);
    const gpu::BufferRange pos4 = output_range(positions_, c), nrm4 = output_range(normals_, c);
    if (plan_ == PassPlan::Fused) {
      limit_normal_sets_.push_back(gpu::DescriptorSet(*p.limit_normal, {last, pos4, nrm4}));
    } else {
      limit_sets_.push_back(gpu::DescriptorSet(*p.limit, {last, pos4}));
      normal_sets_.push_back(gpu::DescriptorSet(*p.normal, {last, nrm4}));
    }
    cut_sets_.push_back(gpu::DescriptorSet(*p.cut_normal, {last, stencils_.range(), nrm}));
  }
}

void VulkanSubdivider::record_image_pass(gpu::Commands& cmd, const gpu::ComputePipeline& pipeline,
                                         const gpu::DescriptorSet& set, int src_side, int dst_side,
                                         ImageWork work) const {
  uint64_t width = 0, rows = 0;  // of invocations
  switch (work) {
    case ImageWork::PerSample: width = rows = uint64_t(dst_side); break;
    case ImageWork::PerSourceSample: width = rows = uint64_t(src_side); break;
    case ImageWork::PerBlock:  // 2 rows x 4 columns (average.glsl)
      width = (uint64_t(dst_side) + 3) / 4, rows = (uint64_t(dst_side) + 1) / 2;
      break;
    case ImageWork::PerSourceBlock: width = rows = uint64_t(src_side - 1); break;
  }
  cmd.bind(pipeline, set);
  cmd.push(Push{uint32_t(src_side), uint32_t(dst_side), 0, uint32_t(dst_side)});
  cmd.dispatch(row_groups(width, rows));
}

void VulkanSubdivider::record_output_pass(gpu::Commands& cmd, const gpu::ComputePipeline& pipeline,
                                          const std::vector<gpu::DescriptorSet>& sets, int src_side,
                                          OutputWork work, const gpu::ComputePipeline* row_ends) const {
  const uint64_t n = uint64_t(src_side - 2);
  const auto each_chunk = [&](const auto& dispatch) {
    for (size_t i = 0; i < outputs_.chunks.size(); ++i) {
      const gpu::Chunk& c = outputs_.chunks[i];
      const uint64_t first_row = c.first_element / n, rows = c.elements / n;
      cmd.bind(sets[i]);
      cmd.push(Push{uint32_t(src_side), uint32_t(n), uint32_t(first_row), uint32_t(rows)});
      dispatch(c, rows);
    }
  };
  cmd.bind(pipeline);
  each_chunk([&](const gpu::Chunk& c, uint64_t) {
    if (work == OutputWork::EveryVertex)
      cmd.dispatch(gpu::groups_for((c.elements + kOutputGroup - 1) / kOutputGroup, kLocalSize, ctx_.limits()));
    else
      cmd.dispatch(1);  // four invocations, one per cut vertex
  });
  if (!row_ends) return;
  // The blocks holding a row's end again, one invocation per row, over what the first wrote.
  cmd.barrier(gpu::Stage::Compute, gpu::Stage::Compute);
  cmd.bind(*row_ends);
  each_chunk([&](const gpu::Chunk&, uint64_t rows) { cmd.dispatch(gpu::groups_for(rows, kLocalSize, ctx_.limits())); });
}

// g^0 -> g^k, one level after the other; every pass reads what the one before wrote.
void VulkanSubdivider::record_levels(gpu::Commands& cmd) {
  const Pipelines& p = *pipelines_;
  for (int k = 0; k < levels_; ++k) {
    const int src = images_[k].side, dst = images_[k + 1].side;
    const std::string level = std::to_string(k + 1);
    cmd.barrier(gpu::Stage::Compute, gpu::Stage::Compute);
    if (plan_ == PassPlan::Fused) {
      frame_timer_.begin(cmd, gpu::PassKind::Kernel, "L+A " + level);
      record_image_pass(cmd, *p.split_average, fused_sets_[k], src, dst, ImageWork::PerSourceBlock);
      frame_timer_.end(cmd);
      continue;
    }
    const int split = 2 * src - 1;
    frame_timer_.begin(cmd, gpu::PassKind::Kernel, "L " + level);
    record_image_pass(cmd, *p.split, split_sets_[k], src, split, ImageWork::PerSourceSample);
    frame_timer_.end(cmd);
    cmd.barrier(gpu::Stage::Compute, gpu::Stage::Compute);
    frame_timer_.begin(cmd, gpu::PassKind::Kernel, "A " + level);
    record_image_pass(cmd, *p.average, average_sets_[k], split, dst, ImageWork::PerBlock);
    frame_timer_.end(cmd);
  }
}

// p^k and n^k from g^k, then the cut-vertex normals over the normal pass's zero tangents.
void VulkanSubdivider::record_outputs(gpu::Commands& cmd) {
  const Pipelines& p = *pipelines_;
  const int side = images_[levels_].side;
  cmd.barrier(gpu::Stage::Compute, gpu::Stage::Compute);
  if (plan_ == PassPlan::Fused) {
    frame_timer_.begin(cmd, gpu::PassKind::Kernel, "E+T");
    record_output_pass(cmd, *p.limit_normal, limit_normal_sets_, side, OutputWork::EveryVertex, p.limit_normal_ends.get());
    frame_timer_.end(cmd);
  } else {
    frame_timer_.begin(cmd, gpu::PassKind::Kernel, "E");
    record_output_pass(cmd, *p.limit, limit_sets_, side, OutputWork::EveryVertex, p.limit_ends.get());
    frame_timer_.end(cmd);
    frame_timer_.begin(cmd, gpu::PassKind::Kernel, "T");
    record_output_pass(cmd, *p.normal, normal_sets_, side, OutputWork::EveryVertex, p.normal_ends.get());
    frame_timer_.end(cmd);
  }
  if (side < 7) return;  // a 3 x 3 image (the octahedron) has no cut-vertex stencil (masks.cpp)
  cmd.barrier(gpu::Stage::Compute, gpu::Stage::Compute);
  frame_timer_.begin(cmd, gpu::PassKind::Kernel, "cut-vertex normals");
  record_output_pass(cmd, *p.cut_normal, cut_sets_, side, OutputWork::CutVertices);
  frame_timer_.end(cmd);
}

void VulkanSubdivider::record_frame() {
  frame_ = ctx_.record([&](gpu::Commands& cmd) {
    // The previous frame and readback read what this frame overwrites.
    cmd.barrier(gpu::Stage::All, gpu::Stage::All);
    frame_timer_.reset(cmd);
    frame_timer_.begin(cmd, gpu::PassKind::Upload, "upload");
    cmd.upload(control_staging_, control_);
    frame_timer_.end(cmd);
    frame_timer_.begin(cmd, gpu::PassKind::Kernel, "pad");
    record_image_pass(cmd, *pipelines_->pad, pad_set_, 0, images_[0].side, ImageWork::PerSample);
    frame_timer_.end(cmd);
    record_levels(cmd);
    record_outputs(cmd);
  });
}

void VulkanSubdivider::record_readback() {
  readback_ = ctx_.record([&](gpu::Commands& cmd) {
    readback_timer_.reset(cmd);
    readback_timer_.begin(cmd, gpu::PassKind::Readback, "readback");
    cmd.download(positions_, positions_staging_);
    cmd.download(normals_, normals_staging_);
    readback_timer_.end(cmd);
  });
}

void VulkanSubdivider::run(const Point3* control) {
  control_staging_.write(control, control_vertices_ * sizeof(Point3));
  ctx_.submit(*frame_);
}

void VulkanSubdivider::read_back(Point3* positions, Point3* normals) {
  ctx_.submit(*readback_);
  read_back_ = true;
  const uint64_t n = uint64_t(size(levels_));
  positions_staging_.read(positions, n * n * sizeof(Point3));
  normals_staging_.read(normals, n * n * sizeof(Point3));
}

std::optional<std::vector<gpu::PassTimestamps>> VulkanSubdivider::timestamps() const {
  auto passes = frame_timer_.read_passes();
  if (!passes) return std::nullopt;
  if (read_back_)
    if (auto readback = readback_timer_.read_passes())
      passes->insert(passes->end(), readback->begin(), readback->end());
  return passes;
}

std::optional<GpuTimes> VulkanSubdivider::times() const {
  auto passes = timestamps();
  if (!passes) return std::nullopt;
  return gpu::to_gpu_times(*passes);
}

PaddedImage VulkanSubdivider::level(int k) const {
  const DeviceImage& image = images_.at(static_cast<size_t>(k));
  PaddedImage out(image.side);
  const size_t count = size_t(image.side) * size_t(image.side);
  const std::vector<float> texels = gpu::download_as<float>(ctx_, image.texels, 4 * count);
  for (int c = 0; c < 3; ++c)
    for (size_t i = 0; i < count; ++i) out.plane(c)[i] = texels[4 * i + c];
  return out;
}

}  // namespace sdb::gim
