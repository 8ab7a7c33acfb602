// VulkanSubdivider: the Subdivider's per-frame work (subdivision.h) as Vulkan compute passes, one
// dispatch per mask and level as the paper's fragment programs (PassPlan::PerMask: pad; L, A per
// level; E; T) or fused (PassPlan::Fused: pad; L+A per level; E+T), then the cut-vertex normals.
// The shaders (shaders/*.comp) mirror masks.cpp operation for operation with `precise`, so the
// padded images and the positions equal the CPU's bit for bit where the device rounds float32
// addition and multiplication correctly (Vulkan requires it); normals go through a division and a
// square root, which Vulkan lets a device round within a few ulp.
//
// Buffers are made once: g^0 .. g^k as three storage buffers each (one per coordinate plane, the
// CPU's planes exactly; one binding per plane keeps images three times larger than a binding
// usable), the split image L[g^{k-1}] for the per-mask plan, and p^k, n^k as packed float3 in
// device-local buffers that a draw can bind as vertex buffers (the paper's RENDER_TO_VERTEX).
// Outputs larger than one binding are written in chunks (gpu::plan_chunks), one dispatch each.
// The frame (upload, passes) and the readback are two recorded command buffers, each timed pass
// by pass with a GpuTimer.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "harness/gpu/gpu.h"
#include "schemes/geometry-image/masks.h"
#include "schemes/geometry-image/subdivision.h"

namespace sdb::gim {

struct VulkanSubdividerOptions {
  // Caps the bytes of one output binding below the device's maxStorageBufferRange (0: no cap), so
  // that tests reach the chunked output path on small outputs.
  uint64_t max_output_chunk_bytes = 0;
  // Caps the bytes an image pass may write through one storage binding (0: maxStorageBufferRange);
  // past it the image passes write through texel views (destination_planes.glsl), so that tests
  // reach that path on small images.
  uint64_t max_image_binding_bytes = 0;
};

class VulkanSubdivider {
 public:
  // Why `ctx`'s device cannot subdivide an n0 x n0 image `levels` times with `plan` (a plane past
  // one binding, an output past one buffer, more memory than the device has), or nullopt.
  static std::optional<std::string> unsupported(const gpu::Context& ctx, int base_size, int levels, PassPlan plan);

  // Throws gpu::Unsupported with unsupported()'s reason, gpu::VulkanError when Vulkan fails.
  VulkanSubdivider(gpu::Context& ctx, int base_size, int levels, PassPlan plan, VulkanSubdividerOptions options = {});
  ~VulkanSubdivider();
  VulkanSubdivider(const VulkanSubdivider&) = delete;
  VulkanSubdivider& operator=(const VulkanSubdivider&) = delete;

  int levels() const { return levels_; }
  int size(int k) const { return level_size(base_size_, k); }
  PassPlan plan() const { return plan_; }
  size_t output_chunks() const { return outputs_.chunks.size(); }
  bool texel_destinations() const { return texel_destinations_; }

  // One frame: the control positions of g0 (closed-mesh vertex order, CutSymmetry::num_vertices()
  // of them) into the upload buffer, then the recorded upload and passes; waits for the device.
  void run(const Point3* control);
  // p^k and n^k of the last run, size(levels())^2 each, row-major: the recorded readback, then a
  // copy out of the mapped readback buffers.
  void read_back(Point3* positions, Point3* normals);
  // Pass times of the last run() and read_back(), in recorded order; nullopt without timestamps.
  std::optional<std::vector<gpu::PassTimestamps>> timestamps() const;
  std::optional<GpuTimes> times() const;

  // Padded g^k of the last run, downloaded (blocking; for tests).
  PaddedImage level(int k) const;
  // Device-local p^k and n^k (packed float3; storage and vertex usage).
  const gpu::Buffer& positions() const { return positions_; }
  const gpu::Buffer& normals() const { return normals_; }

 private:
  struct DeviceImage {  // one padded image: side^2 vec4 texels, (x, y, z, 0) per sample
    int side = 0;
    gpu::Buffer texels;
  };
  struct Pipelines;

  DeviceImage make_image(int side, const std::string& name) const;
  // The binding an image pass writes `image` through (destination_planes.glsl).
  gpu::BufferRange destination(const DeviceImage& image) const;
  void make_pipelines();
  void make_descriptor_sets();
  void record_frame();
  void record_readback();
  void record_levels(gpu::Commands& cmd);
  void record_outputs(gpu::Commands& cmd);
  // What one invocation of an image pass covers: a destination sample (pad), a source sample and
  // the 2 x 2 destination block it splits into (L), a 2 x 2 block of destination samples (A), or
  // the 2 x 2 block a source sample but the last row and column owns (L+A).
  enum class ImageWork { PerSample, PerSourceSample, PerBlock, PerSourceBlock };
  void record_image_pass(gpu::Commands& cmd, const gpu::ComputePipeline& pipeline, const gpu::DescriptorSet& set,
                         int src_side, int dst_side, ImageWork work) const;
  // Output passes run over every vertex of each chunk, or (the cut-vertex normals) over four; with
  // `row_ends`, a second dispatch over the blocks holding a row's end (output_grid.glsl).
  enum class OutputWork { EveryVertex, CutVertices };
  void record_output_pass(gpu::Commands& cmd, const gpu::ComputePipeline& pipeline,
                          const std::vector<gpu::DescriptorSet>& sets, int src_side,
                          OutputWork work = OutputWork::EveryVertex,
                          const gpu::ComputePipeline* row_ends = nullptr) const;

  gpu::Context& ctx_;
  int base_size_, levels_;
  PassPlan plan_;
  // The largest image is past one storage binding: image passes write through texel views.
  bool texel_destinations_ = false;
  size_t control_vertices_ = 0;
  std::array<CutVertexStencil, 4> cut_stencils_{};

  gpu::Buffer control_staging_, control_, gather_, stencils_;
  std::vector<DeviceImage> images_;  // g^0 .. g^k
  DeviceImage split_;                // L[g^k] (per-mask plan), sized for the largest level
  gpu::ChunkPlan outputs_;      // chunks of p^k and n^k (the same for both)
  gpu::Buffer positions_, normals_, positions_staging_, normals_staging_;

  std::unique_ptr<Pipelines> pipelines_;
  gpu::DescriptorSet pad_set_;
  std::vector<gpu::DescriptorSet> split_sets_, average_sets_, fused_sets_;                   // per level k -> k + 1
  std::vector<gpu::DescriptorSet> limit_sets_, normal_sets_, limit_normal_sets_, cut_sets_;  // per output chunk

  gpu::GpuTimer frame_timer_, readback_timer_;
  std::optional<gpu::Recording> frame_, readback_;
  bool read_back_ = false;  // the readback ran at least once (its timer has results)
};

}  // namespace sdb::gim
