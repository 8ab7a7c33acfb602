#include "schemes/fragments/vulkan.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <map>

#include "harness/gpu/gpu.h"
#include "schemes/fragments/device_tables.h"
#include "schemes/fragments/pass_plan.h"
#include "schemes/fragments/surface.h"
#include "sdb_scheme_fragments_shaders.h"

namespace sdb::fragments {
namespace {

namespace shaders = sdb_scheme_fragments_shaders;
using gpu::BufferUsage;

// Invocations per work group, one fragment each (the shaders' local_size_x_id = 0); a batch holds
// up to that many fragments (device_batches). Also on lavapipe: one subgroup a work group
// (gpu::work_group_size) ran fewer instructions (frog stand-in at depth 4: 892 -> 814 M) but took
// longer (the limit 42-47 -> 61-73 ms, paired runs), with either order of batches and chunks.
constexpr uint32_t kLocalSize = 64;
// Scratch of a wave, both halves (a level and the next) and the net points (a third): past this,
// fragments run in more waves.
// Small enough for lavapipe's 2 GiB heap beside a large output, large enough that a real GPU
// runs one wave.
constexpr uint64_t kMaxScratchBytes = uint64_t(512) << 20;
constexpr uint32_t kCatmark = 1, kProject = 2;

struct Push {
  uint32_t level = 0, levels = 0, first_batch = 0, src_base = 0, dst_base = 0, header_words = 0,
           wave_first_vertex = 0, out_shift = 0, chunk = 0, kind_pairs = 0, items = 0, pad = 0;
  float origin[4] = {0, 0, 0, 0};
};

// Consecutive batches, with their contiguous output.
struct Wave {
  uint32_t first_batch = 0, num_batches = 0;
  uint64_t first_vertex = 0, num_vertices = 0;
  uint64_t bind_offset = 0, bind_bytes = 0;  // the output bindings' range (aligned start)
  uint32_t shift = 0;                        // floats from bind_offset to the wave's first vertex
};

// A scratch slot: one point, (x, y, z, 0), read by one texel fetch and stored as one vec4.
constexpr uint64_t kSlotBytes = 16;

struct WavePlan {
  std::vector<Wave> waves;
  std::vector<uint32_t> scratch_offset;  // per batch: its first slot in its wave's scratch
  uint64_t scratch_bytes = 0;            // of the largest wave, for the scratch buffers
};

uint64_t batch_vertices(const FragmentSurface& s, const FragmentSurface::Batch& b) {
  uint64_t n = 0;
  const uint64_t bs = uint64_t(block_size(s.rule, s.depth));
  for (uint32_t i = b.begin; i < b.begin + b.count; ++i) n += s.partition.fragments[s.order[i]].owned_faces.size() * bs;
  return n;
}

// The shapes of a batch's fragments, each once.
std::vector<uint32_t> shapes_of(const FragmentSurface& s, const FragmentSurface::Batch& b) {
  std::vector<uint32_t> shapes;
  for (uint32_t i = b.begin; i < b.begin + b.count; ++i)
    shapes.push_back(uint32_t(s.partition.fragments[s.order[i]].shape));
  std::sort(shapes.begin(), shapes.end());
  shapes.erase(std::unique(shapes.begin(), shapes.end()), shapes.end());
  return shapes;
}

// A batch's scratch: the most slots of its shapes, for each of its fragments (a slot is a row of
// `count` lanes).
uint64_t batch_scratch_bytes(const FragmentSurface& s, const FragmentSurface::Batch& b) {
  uint64_t slots = 0;
  for (uint32_t shape : shapes_of(s, b)) slots = std::max<uint64_t>(slots, s.tables[shape].max_slots);
  return slots * b.count * kSlotBytes;
}

// The surface's batches of one shape each, with runs of consecutive batches smaller than a
// subgroup joined into one of several shapes (up to `local_size` fragments): lavapipe runs a
// subgroup of 8 for a batch of 1, and the frog stand-in's 75 batches of 1 to 7 fragments (its
// vertex patches' shapes) were 62% of its subgroups' work at 1.5 fragments each. Each invocation
// reads its own fragment's shape (fragments.glsl); consecutive batches keep the output contiguous.
std::vector<FragmentSurface::Batch> device_batches(const FragmentSurface& s, uint32_t local_size, uint32_t lanes) {
  std::vector<FragmentSurface::Batch> out;
  bool joinable = false;  // the last batch in `out` is of small batches
  for (const FragmentSurface::Batch& b : s.batches_of(local_size)) {
    const bool small = b.count < lanes;
    if (small && joinable && out.back().count + b.count <= local_size) {
      out.back().count += b.count;
      continue;
    }
    out.push_back(b);
    joinable = small;
  }
  return out;
}

void place_output(Wave& w, uint64_t alignment) {
  const uint64_t first_byte = w.first_vertex * sizeof(Point3);
  w.bind_offset = first_byte - first_byte % alignment;
  w.shift = static_cast<uint32_t>((first_byte - w.bind_offset) / sizeof(float));
  w.bind_bytes = w.num_vertices * sizeof(Point3) + (first_byte - w.bind_offset);
}

// Consecutive batches while their scratch and output fit one binding each (and the dispatch's y).
WavePlan plan_waves(const FragmentSurface& s, const std::vector<FragmentSurface::Batch>& batches,
                    const gpu::DeviceLimits& limits, uint64_t max_wave_bytes, const std::string& device) {
  // The output bindings are r32f texel views: their offsets align for those.
  const uint64_t alignment = std::max<uint64_t>(limits.min_texel_buffer_offset_alignment, 4);
  const uint64_t range = max_wave_bytes ? std::min(max_wave_bytes, limits.max_storage_buffer_range)
                                        : limits.max_storage_buffer_range;
  // The scratch binding holds two halves (a level and the next); the net points a third, apart.
  const uint64_t scratch_cap =
      std::min({range / 2, kMaxScratchBytes / 3, limits.max_memory_allocation_size / 2}) / kSlotBytes * kSlotBytes;
  WavePlan plan;
  Wave w;
  uint64_t scratch = 0;
  for (uint32_t i = 0; i < batches.size(); ++i) {
    const uint64_t n = batch_vertices(s, batches[i]), need = batch_scratch_bytes(s, batches[i]);
    if (n * sizeof(Point3) + alignment > range || need > scratch_cap)
      throw gpu::Unsupported("one batch of fragments writes " + gpu::gib_text(n * sizeof(Point3)) + " and needs " +
                             gpu::gib_text(2 * need) + " of scratch; " + device + " binds " + gpu::gib_text(range) +
                             " at once");
    if (w.num_batches == limits.max_compute_work_group_count[1] || scratch + need > scratch_cap ||
        (w.num_vertices + n) * sizeof(Point3) + alignment > range) {
      plan.waves.push_back(w);
      plan.scratch_bytes = std::max(plan.scratch_bytes, scratch);
      w = Wave{i, 0, w.first_vertex + w.num_vertices, 0};
      scratch = 0;
    }
    plan.scratch_offset.push_back(static_cast<uint32_t>(scratch / kSlotBytes));
    ++w.num_batches, w.num_vertices += n, scratch += need;
  }
  if (w.num_batches) plan.waves.push_back(w);
  plan.scratch_bytes = std::max({plan.scratch_bytes, scratch, kSlotBytes});
  for (Wave& wave : plan.waves) place_output(wave, alignment);
  return plan;
}

// fragments.glsl's bindings: tables, batches, fragment list, control points, scratch (read),
// positions, normals, scratch (written), net points (read, written). Reads go through texel views
// (lavapipe's fast path), the scratch's and net points' writes as 64-bit words to storage
// buffers, the output's through r32f image views; the batches, one uvec4 per invocation, are a
// storage buffer.
// The rule's flags, the pass's part and its kind are specialization constants: lavapipe runs both
// sides of every branch, masked, unless its condition is a constant.
gpu::ComputePipelineDesc pass(const char* shader, uint32_t flags, Part part, uint32_t key) {
  using gpu::Binding;
  return {shaders::get(shader),
          {Binding::UniformTexelBuffer, Binding::StorageBuffer, Binding::UniformTexelBuffer, Binding::UniformTexelBuffer,
           Binding::UniformTexelBuffer, Binding::StorageTexelBuffer, Binding::StorageTexelBuffer,
           Binding::StorageBuffer, Binding::UniformTexelBuffer, Binding::StorageBuffer, Binding::UniformTexelBuffer},
          sizeof(Push),
          {{0, kLocalSize}, {1, flags}, {2, static_cast<uint32_t>(part)}, {3, key}}};
}

class VulkanFragmentEvaluation final : public Evaluation {
 public:
  VulkanFragmentEvaluation(const ControlMesh& mesh, SubdivisionRule rule, int depth, bool project,
                           VulkanOptions options, std::shared_ptr<gpu::Context> ctx)
      : ctx_(std::move(ctx)),
        control_(mesh.positions),
        surface_(mesh, rule, depth, project ? inner_depth_for(mesh, depth) : depth),
        batches_(device_batches(surface_, kLocalSize, ctx_->limits().subgroup_size)) {
    DeviceTables tables = pack_tables(surface_);
    passes_ = plan_passes(surface_, tables, project, ctx_->info().driver_name == "llvmpipe", ctx_->info().name);
    plan_ = plan_waves(surface_, batches_, ctx_->limits(), options.max_wave_bytes, ctx_->info().name);
    append_work_items(tables);
    const uint64_t output = std::max<uint64_t>(surface_.num_output_vertices * sizeof(Point3), 16);
    const uint64_t scratch = plan_.scratch_bytes;
    gpu::check_memory(*ctx_,
                      {tables.words.size() * 4 + tables.fragments.size() * 4 + batches_.size() * 16 +
                           control_.size() * sizeof(Point3) + 3 * scratch + 2 * output,
                       2 * output + control_.size() * sizeof(Point3)},
                      mesh.name + " at depth " + std::to_string(depth));
    if (output > std::min(ctx_->limits().max_memory_allocation_size, ctx_->limits().max_buffer_size))
      throw gpu::Unsupported("the output's " + gpu::gib_text(output) + " of positions exceed one buffer on " +
                             ctx_->info().name);
    push_.levels = tables.levels;
    push_.header_words = tables.header_words;
    make_buffers(std::move(tables), scratch, output);
    make_pipelines((rule == SubdivisionRule::CatmullClark ? kCatmark : 0) | (project ? kProject : 0));
    surface_.describe(out_);
    if (options.render_width > 0) make_renderer(options);
    const Bounds box = bounds_of(control_);
    for (int k = 0; k < 3; ++k) push_.origin[k] = static_cast<float>(box.centre(k));
    record_frame();
    readback_.emplace(*ctx_, positions_, normals_, output);
    out_.positions.resize(surface_.num_output_vertices);
    out_.normals.resize(surface_.num_output_vertices);
  }

  void execute() override {
    control_staging_.write(control_);
    ctx_->submit(*frame_);
    readback_->invalidate();
  }

  const Tessellation& result() override {
    readback_->read_into(out_);
    return out_;
  }

  size_t bytes_out() const override { return out_.positions.size() * 2 * sizeof(Point3); }

  // Passes of the same name summed over the waves, in the order they first ran.
  std::optional<GpuTimes> gpu_times() const override {
    auto passes = frame_timer_->read_passes();
    if (!passes) return std::nullopt;
    readback_->append_passes(*passes);
    std::vector<gpu::PassTimestamps> merged;
    std::map<std::string, size_t> index;
    for (const gpu::PassTimestamps& p : *passes) {
      auto [it, fresh] = index.emplace(p.label, merged.size());
      if (fresh) merged.push_back(p);
      else merged[it->second].ms += p.ms;
    }
    return gpu::to_gpu_times(merged);
  }

  FragmentStats stats() const {
    FragmentStats s = surface_.stats();
    s.waves = static_cast<int>(plan_.waves.size());
    return s;
  }

 private:
  // Takes the tables: their words go to the device as they are, not copied.
  void make_buffers(DeviceTables tables, uint64_t scratch, uint64_t output) {
    gpu::Context& c = *ctx_;
    std::vector<uint32_t> batch_words;
    for (size_t i = 0; i < batches_.size(); ++i) {
      const FragmentSurface::Batch& b = batches_[i];
      batch_words.insert(batch_words.end(), {0u, b.begin, b.count, plan_.scratch_offset[i]});
    }
    tables.words.resize((tables.words.size() + 3) / 4 * 4, 0);  // whole uvec4 texels for the rules' view
    tables_ = gpu::texel_table(c, std::move(tables.words), "fragments' pattern tables");
    batches_buffer_ = gpu::storage_table(c, batch_words, "fragments' batches");
    fragments_ = gpu::texel_table(c, std::move(tables.fragments), "fragment list");
    const uint64_t control_bytes = std::max<uint64_t>(control_.size() * sizeof(Point3), 16);
    control_staging_ = gpu::Buffer::upload(c, control_bytes, "control points (staging)");
    control_buffer_ = gpu::Buffer::device(c, control_bytes, BufferUsage::UniformTexel, "control points");
    gpu::check_texel_binding(c, 2 * scratch / kSlotBytes, "fragments' scratch");
    scratch_ = gpu::Buffer::device(c, 2 * scratch, BufferUsage::UniformTexel | BufferUsage::Storage,
                                   "scratch (two levels)");
    net_ = gpu::Buffer::device(c, scratch, BufferUsage::UniformTexel | BufferUsage::Storage, "net points");
    const BufferUsage output_usage = BufferUsage::StorageTexel | BufferUsage::Vertex;
    positions_ = gpu::Buffer::device(c, output, output_usage, "positions");
    normals_ = gpu::Buffer::device(c, output, output_usage, "normals");
  }

  void make_renderer(const VulkanOptions& o) {
    target_.emplace(*ctx_, o.render_width, o.render_height);
    renderer_.emplace(*ctx_);
    if (out_.triangles.empty() || out_.triangles.size() > UINT32_MAX)
      throw gpu::Unsupported(std::to_string(out_.triangles.size() / 3) + " triangles: nothing to draw, or past one draw call");
    indices_ = gpu::device_buffer_with(*ctx_, out_.triangles, BufferUsage::Index, "triangle indices");
    const Bounds box = bounds_of(control_);
    camera_ = gpu::frame_bounds({float(box.lo[0]), float(box.lo[1]), float(box.lo[2])},
                                {float(box.hi[0]), float(box.hi[1]), float(box.hi[2])}, target_->aspect());
  }

  // The output as it is on the device, drawn: what a frame of the poster's Table 1 ends with.
  void record_render(gpu::Commands& cmd) {
    cmd.barrier(gpu::Stage::Compute, gpu::Stage::Vertex);
    frame_timer_->begin(cmd, gpu::PassKind::Draw, "render");
    target_->render(cmd, [&](gpu::Commands& c) {
      renderer_->draw(c, {&positions_, &normals_, &indices_, static_cast<uint32_t>(out_.triangles.size())}, camera_);
    });
    frame_timer_->end(cmd);
  }

  // `flags` (kCatmark | kProject) specialize every pipeline, the pass's part and kind each.
  void make_pipelines(uint32_t flags) {
    for (const PassSpec& p : passes_) {
      const char* shader = p.part == Part::Gather  ? "gather.comp"
                           : p.part == Part::Limit ? "limit.comp"
                           : p.part == Part::Patch ? "patch_normals.comp"
                                                   : "level.comp";
      pipelines_.try_emplace({p.part, p.key},
                             gpu::shared_compute_pipeline(*ctx_, pass(shader, flags, p.part, p.key)));
    }
  }

  gpu::DescriptorSet set_for(const gpu::ComputePipeline& p, const Wave& w) const {
    return gpu::DescriptorSet(p, {tables_.texels(VK_FORMAT_R32_UINT), batches_buffer_.range(),
                                  fragments_.texels(VK_FORMAT_R32_UINT), control_buffer_.texels(VK_FORMAT_R32_SFLOAT),
                                  scratch_.texels(VK_FORMAT_R32G32B32A32_SFLOAT),
                                  positions_.texels(VK_FORMAT_R32_SFLOAT, w.bind_offset, w.bind_bytes),
                                  normals_.texels(VK_FORMAT_R32_SFLOAT, w.bind_offset, w.bind_bytes),
                                  scratch_.range(), net_.texels(VK_FORMAT_R32G32B32A32_SFLOAT), net_.range(),
                                  tables_.texels(VK_FORMAT_R32G32B32A32_UINT)});
  }

  // Per wave and pass, its work groups (a chunk of entries for a batch of the wave, two words each),
  // appended to the tables in the order they run (interleave_by_cost); none for an empty chunk.
  void append_work_items(DeviceTables& tables) {
    const uint32_t lanes = std::max<uint32_t>(ctx_->limits().subgroup_size, 1);
    std::vector<std::vector<uint32_t>> shapes;  // per batch, for every pass
    for (const FragmentSurface::Batch& b : batches_) shapes.push_back(shapes_of(surface_, b));
    for (const Wave& w : plan_.waves) {
      items_.emplace_back();
      for (const PassSpec& pass : passes_) {
        std::vector<WorkItem> items;
        for (uint32_t b = w.first_batch; b < w.first_batch + w.num_batches; ++b) {
          // A chunk of a batch of several shapes costs about what its costliest shape's does.
          std::vector<uint64_t> chunks;
          for (uint32_t shape : shapes[b]) {
            const std::vector<uint64_t>& c = pass.chunk_costs[shape];
            chunks.resize(std::max(chunks.size(), c.size()), 0);
            for (size_t k = 0; k < c.size(); ++k) chunks[k] = std::max(chunks[k], c[k]);
          }
          const uint64_t subgroups = (batches_[b].count + lanes - 1) / lanes;
          for (uint32_t c = 0; c < chunks.size(); ++c) items.push_back({c, b - w.first_batch, subgroups * chunks[c]});
        }
        items_.back().push_back({static_cast<uint32_t>(tables.words.size()), static_cast<uint32_t>(items.size())});
        for (const WorkItem& item : interleave_by_cost(items))
          tables.words.insert(tables.words.end(), {item.chunk, item.batch});
      }
    }
    if (tables.words.size() > std::numeric_limits<uint32_t>::max())
      throw gpu::Unsupported("the pattern tables pass 2^32 words");
  }

  // A work group per work item (append_work_items): a chunk of the pass's entries for one batch
  // (its work group's scratch). Levels alternate between the scratch halves: level d is in half d % 2.
  void dispatch(gpu::Commands& cmd, const gpu::ComputePipeline& p, const gpu::DescriptorSet& set, const Wave& w,
                const PassSpec& pass, std::pair<uint32_t, uint32_t> items) {
    if (items.second == 0) return;
    Push push = push_;
    push.level = pass.level;
    push.chunk = pass.chunk;
    push.kind_pairs = pass.kind_pairs;
    const uint32_t half = static_cast<uint32_t>(plan_.scratch_bytes / kSlotBytes);
    const bool last = pass.part == Part::Limit || pass.part == Part::Patch;
    const uint32_t made = last ? push_.levels + 1 : pass.level;  // the level this pass writes
    push.src_base = ((made + 1) % 2) * half;
    push.dst_base = (made % 2) * half;
    push.first_batch = w.first_batch;
    push.wave_first_vertex = static_cast<uint32_t>(w.first_vertex);
    push.out_shift = w.shift;
    cmd.barrier(gpu::Stage::Compute, gpu::Stage::Compute);
    cmd.bind(p, set);
    const uint32_t most = ctx_->limits().max_compute_work_group_count[0];
    for (uint32_t done = 0; done < items.second; done += most) {
      push.items = items.first + 2 * done;
      cmd.push(push);
      cmd.dispatch(std::min(most, items.second - done));
    }
  }

  // Consecutive passes of one label (a level's face, edge and vertex points; the limit's kinds and
  // patch normals) under one timestamp pair.
  void record_wave(gpu::Commands& cmd, size_t i) {
    const Wave& w = plan_.waves[i];
    for (size_t k = 0; k < passes_.size();) {
      const std::string label = pass_label(passes_[k]);
      frame_timer_->begin(cmd, gpu::PassKind::Kernel, label);
      for (; k < passes_.size() && pass_label(passes_[k]) == label; ++k)
        dispatch(cmd, *pipelines_.at({passes_[k].part, passes_[k].key}), sets_[i], w, passes_[k], items_[i][k]);
      frame_timer_->end(cmd);
    }
  }

  void record_frame() {
    const uint32_t levels = push_.levels;
    frame_timer_.emplace(*ctx_, 2 + static_cast<uint32_t>(plan_.waves.size()) * (levels + 2));
    // Every pipeline has the same bindings: one set per wave serves them all.
    for (const Wave& w : plan_.waves) sets_.push_back(set_for(*pipelines_.begin()->second, w));
    frame_ = ctx_->record([&](gpu::Commands& cmd) {
      // The previous frame and readback read what this frame overwrites.
      cmd.barrier(gpu::Stage::All, gpu::Stage::All);
      frame_timer_->reset(cmd);
      frame_timer_->begin(cmd, gpu::PassKind::Upload, "upload");
      cmd.upload(control_staging_, control_buffer_);
      frame_timer_->end(cmd);
      for (size_t i = 0; i < plan_.waves.size(); ++i) record_wave(cmd, i);
      if (target_) record_render(cmd);
    });
  }


  std::shared_ptr<gpu::Context> ctx_;  // outlives every Vulkan object below
  std::vector<Point3> control_;
  FragmentSurface surface_;
  std::vector<FragmentSurface::Batch> batches_;
  std::vector<PassSpec> passes_;
  WavePlan plan_;
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> items_;  // per wave, per pass: first word, count
  Push push_;
  gpu::Buffer tables_, batches_buffer_, fragments_, control_staging_, control_buffer_, scratch_, net_;
  gpu::Buffer positions_, normals_;
  std::optional<gpu::OutputReadback> readback_;
  // Per part and kind; the context's (shared_compute_pipeline: lavapipe compiles each once).
  std::map<std::pair<Part, uint32_t>, std::shared_ptr<const gpu::ComputePipeline>> pipelines_;
  std::vector<gpu::DescriptorSet> sets_;
  std::optional<gpu::GpuTimer> frame_timer_;
  std::optional<gpu::Recording> frame_;
  std::optional<gpu::RenderTarget> target_;
  std::optional<gpu::MeshRenderer> renderer_;
  gpu::Buffer indices_;
  gpu::Camera camera_;
  Tessellation out_;
};

}  // namespace

std::optional<std::string> vulkan_unavailable() {
  static const gpu::DeviceInfo device = gpu::probe();
  if (!device.available) return "no Vulkan device: " + device.reason;
  return std::nullopt;  // three storage buffers and seven texel views per pass: within Vulkan's minimum limits
}

std::unique_ptr<Evaluation> make_vulkan_evaluation(const ControlMesh& mesh, SubdivisionRule rule, int depth,
                                                   bool project_to_limit, VulkanOptions options) {
  if (auto why = vulkan_unavailable()) throw gpu::Unsupported(*why);
  return std::make_unique<VulkanFragmentEvaluation>(mesh, rule, depth, project_to_limit, options,
                                                    gpu::shared_context());
}

std::optional<FragmentStats> vulkan_stats(const Evaluation& e) {
  if (auto* v = dynamic_cast<const VulkanFragmentEvaluation*>(&e)) return v->stats();
  return std::nullopt;
}

}  // namespace sdb::fragments
