// The limit plan (limit.h) on a Vulkan device: its tables uploaded once, and its two passes
// ("limit: regular", "limit: special", each timed; the special pass is one dispatch for each table,
// the last level's and the early level's) recorded into a scheme's frame after the pass that wrote
// the level's points. shaders/limit_*.comp are limit.cpp's arithmetic.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "harness/gpu/gpu.h"
#include "harness/refined/limit.h"

namespace sdb::refined {

// Entries in one view of the regular rings: the device's maxTexelBufferElements, or `entries` where
// a test asks for fewer (0: the device's again), so that a small mesh takes the several-view path
// of a 45.8 M-triangle output on lavapipe. For tests only; not thread-safe against frames being made.
void limit_ring_view_entries_for_testing(uint64_t entries);

class VulkanLimit {
 public:
  // Throws Unsupported where a table passes one texel view.
  VulkanLimit(gpu::Context& ctx, const LimitPlan& plan);
  // Device bytes the plan's tables take, for gpu::check_memory before anything is made.
  static uint64_t table_bytes(const LimitPlan& plan);
  // The level's points and the early level's (rgba32f texels; the plan's EarlyLevel, or the
  // level's again where it has none); the output's positions and normals (r32f texels, three
  // floats a vertex).
  void bind(const gpu::Buffer& points, const gpu::Buffer& early_points, const gpu::Buffer& positions,
            const gpu::Buffer& normals);
  // Both passes, each under the timer, positions moved by `origin`.
  void record(gpu::Commands& cmd, gpu::GpuTimer& timer, const float origin[3]) const;

 private:
  gpu::Context* ctx_;
  // A special table on the device.
  struct Table {
    Table(gpu::Context& ctx, const SpecialTable& t, const std::string& level);
    uint32_t count;
    gpu::Buffer vertex, begin, ring, weights;
  };
  uint32_t ring_size_, face_size_, vertices_;
  // The regular rings in views of at most maxTexelBufferElements entries (the sword's depth 5 has
  // 183 M, lavapipe's view 134 M): one dispatch of the regular pass per view.
  gpu::ChunkPlan ring_chunks_;
  std::vector<gpu::Buffer> regular_ring_;
  Table special_, early_;
  std::shared_ptr<const gpu::ComputePipeline> regular_, special_pass_;
  std::vector<gpu::DescriptorSet> regular_sets_;
  gpu::DescriptorSet set_, early_set_;
};

}  // namespace sdb::refined
