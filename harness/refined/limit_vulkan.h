// The limit plan (limit.h) on a Vulkan device: its tables uploaded once, and its two passes
// ("limit: regular", "limit: special", each timed; the special pass is one dispatch for each table,
// the last level's and the early level's) recorded into a scheme's frame after the pass that wrote
// the level's points. shaders/limit_*.comp are limit.cpp's arithmetic.
#pragma once

#include <memory>
#include <string>

#include "harness/gpu/gpu.h"
#include "harness/refined/limit.h"

namespace sdb::refined {

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
  gpu::Buffer regular_ring_;
  Table special_, early_;
  std::shared_ptr<const gpu::ComputePipeline> regular_, special_pass_;
  gpu::DescriptorSet set_, early_set_;
};

}  // namespace sdb::refined
