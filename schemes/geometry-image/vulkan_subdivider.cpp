#include "schemes/geometry-image/vulkan_subdivider.h"

#include <algorithm>
#include <cstdio>
#include <initializer_list>
#include <stdexcept>

#include "sdb_scheme_geometry_image_shaders.h"

namespace sdb::gim {

namespace {

namespace shaders = sdb_scheme_geometry_image_shaders;
using gpu::Binding;
using gpu::BufferUsage;

// Invocations per work group (the shaders' local_size_x_id = 0).
constexpr uint32_t kLocalSize = 64;
static_assert(kLocalSize >= 4 && kLocalSize % 2 == 0,
              "the cut-vertex pass runs its four invocations in one work group; "
              "L gives half of each group the even columns, half the odd ones");
// The most storage buffers one pass binds (an image pass: three source and three destination planes).
constexpr uint32_t kMaxBindings = 6;

// The shaders' push constants (gim_common.glsl).
struct Push {
  uint32_t src_side = 0, dst_side = 0, first_row = 0, rows = 0;
};

// Work groups for `rows` rows of `width` samples: x along a row, one row of groups per row.
gpu::Groups row_groups(uint64_t width, uint64_t rows) {
  return {static_cast<uint32_t>((width + kLocalSize - 1) / kLocalSize), static_cast<uint32_t>(rows), 1};
}

uint64_t plane_bytes(int side) { return uint64_t(side) * uint64_t(side) * sizeof(float); }

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

// Images are read through float texel views (source_planes.glsl) and written through r32f
// storage texel views (destination_planes.glsl, output_grid.glsl); tables stay storage buffers.
constexpr Binding kRead = Binding::UniformTexelBuffer, kWrite = Binding::StorageTexelBuffer,
                  kTable = Binding::StorageBuffer;
const BufferUsage kPlaneUsage = BufferUsage::UniformTexel | BufferUsage::StorageTexel;

gpu::ComputePipelineDesc pass(const char* shader, std::vector<Binding> bindings) {
  return {shaders::get(shader), std::move(bindings), sizeof(Push), {{0, kLocalSize}}};
}

// The pipeline's bindings' ranges: texel bindings get a float (R32) view.
gpu::DescriptorSet set_of(const gpu::ComputePipeline& pipeline, std::vector<gpu::BufferRange> ranges) {
  for (size_t i = 0; i < ranges.size() && i < pipeline.bindings().size(); ++i)
    if (pipeline.bindings()[i] != Binding::StorageBuffer) ranges[i].texel_format = VK_FORMAT_R32_SFLOAT;
  return gpu::DescriptorSet(pipeline, ranges);
}

std::vector<gpu::BufferRange> ranges_of(std::initializer_list<const gpu::Buffer*> buffers) {
  std::vector<gpu::BufferRange> ranges;
  for (const gpu::Buffer* b : buffers) ranges.push_back(b->range());
  return ranges;
}

}  // namespace

// The pipelines a plan uses; the others stay empty.
struct VulkanSubdivider::Pipelines {
  std::optional<gpu::ComputePipeline> pad, split, average, split_average, limit, normal, limit_normal, cut_normal;
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
  const uint64_t plane = plane_bytes(widest);
  const std::string image = "a " + std::to_string(base_size) + " x " + std::to_string(base_size) + " image at depth " +
                            std::to_string(levels);
  if (plane > std::min(limits.max_storage_buffer_range, largest_buffer) || uint64_t(widest) * widest > UINT32_MAX)
    return image + " needs padded image planes of " + std::to_string(widest) + " x " + std::to_string(widest) +
           " floats (" + mib_text(plane) + ") in one binding; " + device + " binds at most " +
           mib_text(std::min(limits.max_storage_buffer_range, largest_buffer));
  if (uint64_t(widest) * widest > limits.max_texel_buffer_elements)
    return image + " reads padded image planes of " + std::to_string(widest) + " x " + std::to_string(widest) +
           " floats through texel views; " + device + " allows " + std::to_string(limits.max_texel_buffer_elements) +
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
  for (int side : sides) total += 3 * plane_bytes(side);
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

  for (int k = 0; k <= levels; ++k) images_.push_back(make_planes(size(k) + 2, "g^" + std::to_string(k)));
  if (plan == PassPlan::PerMask && levels > 0) split_ = make_planes(2 * images_[levels - 1].side - 1, "L[g^k]");

  const uint64_t n = uint64_t(size(levels));
  // Chunks of whole rows: an output pass dispatches a row of work groups per row.
  outputs_ = gpu::plan_chunks(ctx.limits(), {n * n, sizeof(Point3), n, kLocalSize, options.max_output_chunk_bytes});
  if (outputs_.buffer_bytes.size() != 1)
    throw gpu::Unsupported("the positions of a " + std::to_string(n) + " x " + std::to_string(n) +
                           " grid do not fit one buffer of " + ctx.info().name);
  const uint64_t output_bytes = outputs_.buffer_bytes[0];
  const BufferUsage output_usage = BufferUsage::Storage | BufferUsage::StorageTexel | BufferUsage::Vertex;
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

VulkanSubdivider::Planes VulkanSubdivider::make_planes(int side, const std::string& name) const {
  Planes p;
  p.side = side;
  const char* axes[] = {"x", "y", "z"};
  for (int c = 0; c < 3; ++c)
    p.plane[c] = gpu::Buffer::device(ctx_, plane_bytes(side), kPlaneUsage, name + " plane " + axes[c]);
  return p;
}

void VulkanSubdivider::make_pipelines() {
  pipelines_ = std::make_unique<Pipelines>();
  Pipelines& p = *pipelines_;
  p.pad.emplace(ctx_, pass("pad.comp", {kTable, kTable, kWrite, kWrite, kWrite}));
  p.cut_normal.emplace(ctx_, pass("cut_normal.comp", {kRead, kRead, kRead, kTable, kTable}));
  const std::vector<Binding> image_to_image = {kRead, kRead, kRead, kWrite, kWrite, kWrite};
  if (plan_ == PassPlan::Fused) {
    p.split_average.emplace(ctx_, pass("split_average.comp", image_to_image));
    p.limit_normal.emplace(ctx_, pass("limit_normal.comp", {kRead, kRead, kRead, kWrite, kWrite}));
  } else {
    p.split.emplace(ctx_, pass("split.comp", image_to_image));
    p.average.emplace(ctx_, pass("average.comp", image_to_image));
    p.limit.emplace(ctx_, pass("limit.comp", {kRead, kRead, kRead, kWrite}));
    p.normal.emplace(ctx_, pass("normal.comp", {kRead, kRead, kRead, kWrite}));
  }
}

void VulkanSubdivider::make_descriptor_sets() {
  const Pipelines& p = *pipelines_;
  auto planes = [](const Planes& a) { return std::vector<const gpu::Buffer*>{&a.plane[0], &a.plane[1], &a.plane[2]}; };
  auto image_to_image = [&](const gpu::ComputePipeline& pipeline, const Planes& src, const Planes& dst) {
    return set_of(pipeline, ranges_of({&src.plane[0], &src.plane[1], &src.plane[2], &dst.plane[0], &dst.plane[1],
                                       &dst.plane[2]}));
  };
  const Planes& g0 = images_[0];
  pad_set_ = set_of(*p.pad, ranges_of({&gather_, &control_, &g0.plane[0], &g0.plane[1], &g0.plane[2]}));
  for (int k = 0; k < levels_; ++k) {
    if (plan_ == PassPlan::Fused) {
      fused_sets_.push_back(image_to_image(*p.split_average, images_[k], images_[k + 1]));
    } else {
      split_sets_.push_back(image_to_image(*p.split, images_[k], split_));
      average_sets_.push_back(image_to_image(*p.average, split_, images_[k + 1]));
    }
  }
  // Output passes: the last image's planes, then the chunk's part of the outputs.
  const std::vector<const gpu::Buffer*> last = planes(images_[levels_]);
  auto output_set = [&](const gpu::ComputePipeline& pipeline, std::vector<gpu::BufferRange> outputs) {
    std::vector<gpu::BufferRange> ranges;
    for (const gpu::Buffer* b : last) ranges.push_back(b->range());
    ranges.insert(ranges.end(), outputs.begin(), outputs.end());
    return set_of(pipeline, ranges);
  };
  for (const gpu::Chunk& c : outputs_.chunks) {
    const gpu::BufferRange pos = positions_.range(c.byte_offset, c.bytes), nrm = normals_.range(c.byte_offset, c.bytes);
    if (plan_ == PassPlan::Fused) {
      limit_normal_sets_.push_back(output_set(*p.limit_normal, {pos, nrm}));
    } else {
      limit_sets_.push_back(output_set(*p.limit, {pos}));
      normal_sets_.push_back(output_set(*p.normal, {nrm}));
    }
    cut_sets_.push_back(output_set(*p.cut_normal, {stencils_.range(), nrm}));
  }
}

void VulkanSubdivider::record_image_pass(gpu::Commands& cmd, const gpu::ComputePipeline& pipeline,
                                         const gpu::DescriptorSet& set, int src_side, int dst_side,
                                         ImageWork work) const {
  // One invocation per destination sample, or (L+A) per 2 x 2 destination block: per source
  // sample but the last row and column.
  const uint64_t side = work == ImageWork::PerSample ? uint64_t(dst_side) : uint64_t(src_side - 1);
  cmd.bind(pipeline, set);
  cmd.push(Push{uint32_t(src_side), uint32_t(dst_side), 0, uint32_t(dst_side)});
  cmd.dispatch(row_groups(side, side));
}

void VulkanSubdivider::record_output_pass(gpu::Commands& cmd, const gpu::ComputePipeline& pipeline,
                                          const std::vector<gpu::DescriptorSet>& sets, int src_side,
                                          OutputWork work) const {
  const uint64_t n = uint64_t(src_side - 2);
  cmd.bind(pipeline);
  for (size_t i = 0; i < outputs_.chunks.size(); ++i) {
    const gpu::Chunk& c = outputs_.chunks[i];
    const uint64_t first_row = c.first_element / n, rows = c.elements / n;
    cmd.bind(sets[i]);
    cmd.push(Push{uint32_t(src_side), uint32_t(n), uint32_t(first_row), uint32_t(rows)});
    if (work == OutputWork::EveryVertex)
      cmd.dispatch(row_groups(n, rows));
    else
      cmd.dispatch(1);  // four invocations, one per cut vertex
  }
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
      record_image_pass(cmd, *p.split_average, fused_sets_[k], src, dst, ImageWork::PerBlock);
      frame_timer_.end(cmd);
      continue;
    }
    const int split = 2 * src - 1;
    frame_timer_.begin(cmd, gpu::PassKind::Kernel, "L " + level);
    record_image_pass(cmd, *p.split, split_sets_[k], src, split);
    frame_timer_.end(cmd);
    cmd.barrier(gpu::Stage::Compute, gpu::Stage::Compute);
    frame_timer_.begin(cmd, gpu::PassKind::Kernel, "A " + level);
    record_image_pass(cmd, *p.average, average_sets_[k], split, dst);
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
    record_output_pass(cmd, *p.limit_normal, limit_normal_sets_, side);
    frame_timer_.end(cmd);
  } else {
    frame_timer_.begin(cmd, gpu::PassKind::Kernel, "E");
    record_output_pass(cmd, *p.limit, limit_sets_, side);
    frame_timer_.end(cmd);
    frame_timer_.begin(cmd, gpu::PassKind::Kernel, "T");
    record_output_pass(cmd, *p.normal, normal_sets_, side);
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
    record_image_pass(cmd, *pipelines_->pad, pad_set_, 0, images_[0].side);
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
  const Planes& image = images_.at(static_cast<size_t>(k));
  PaddedImage out(image.side);
  const uint64_t count = uint64_t(image.side) * uint64_t(image.side);
  for (int c = 0; c < 3; ++c) gpu::download(ctx_, image.plane[c], out.plane(c), count * sizeof(float));
  return out;
}

}  // namespace sdb::gim
