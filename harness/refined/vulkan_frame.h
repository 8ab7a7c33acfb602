// The Vulkan frame the uniform-refinement peers share (schemes/halfedge, schemes/edgefriend):
// the control points uploaded relative to the levels' origin (float keeps its precision there),
// the scheme's own passes, then the limit projection (limit_vulkan.h) or the last level's points
// as they are ("output"), every pass timed, and the output read back outside the frame. A scheme
// derives from it, makes its levels' buffers and records its passes; what was the same in both
// schemes' vulkan.cpp (the output buffers and their checks, the frame's head and tail, the
// readback and the timings) is here once.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/scheme.h"
#include "harness/gpu/gpu.h"
#include "harness/refined/limit.h"
#include "harness/refined/limit_vulkan.h"

namespace sdb::refined {

class VulkanFrame : public Evaluation {
 public:
  void execute() final;
  const Tessellation& result() final;
  size_t bytes_out() const final { return out_->positions.size() * 2 * sizeof(Point3); }
  std::optional<GpuTimes> gpu_times() const final;

 protected:
  // The uploaded points are `control`[order[i]] (`order` empty: every control point in order),
  // moved by -origin; `out` (positions and normals sized) receives the frame's output.
  VulkanFrame(std::shared_ptr<gpu::Context> ctx, std::vector<Point3> control, std::vector<uint32_t> order,
              const float origin[3], Tessellation& out);

  gpu::Context& ctx() { return *ctx_; }
  // Points uploaded each frame (rgba32f texels).
  uint32_t uploaded() const { return static_cast<uint32_t>(relative_.size()); }

  // Before anything is made: the output's floats against one texel view, and the device's memory
  // for `scheme_bytes` of the scheme's own buffers, the plan's tables (`plan` null: no
  // projection) and the output; `what` names the request in the refusal.
  void check_device(uint64_t scheme_bytes, const LimitPlan* plan, const std::string& what);
  // The staging buffer of the uploaded points and the output's two buffers.
  void make_output_buffers();
  // The frame's tail, reading the last level's `points` (and the plan's early level's,
  // `early_points`): the plan's projection, or the points as they are where `plan` is null.
  void bind_output(const LimitPlan* plan, const gpu::Buffer& points, const gpu::Buffer& early_points);
  // Records the frame: "upload" into `upload_to`, `passes` (at most `max_passes` timed), the tail.
  void record_frame(const gpu::Buffer& upload_to, uint32_t max_passes,
                    const std::function<void(gpu::Commands&, gpu::GpuTimer&)>& passes);

  static constexpr uint32_t kLocalSize = 64;
  static constexpr VkFormat kPoint = VK_FORMAT_R32G32B32A32_SFLOAT, kWord = VK_FORMAT_R32_UINT,
                            kFloat = VK_FORMAT_R32_SFLOAT;

 private:
  std::shared_ptr<gpu::Context> ctx_;
  std::vector<Point3> control_;
  std::vector<uint32_t> order_;
  float origin_[3];
  Tessellation* out_;
  uint32_t out_vertices_;
  uint64_t output_bytes_ = 0;
  std::vector<std::array<float, 4>> relative_;
  gpu::Buffer staging_, positions_, normals_;
  std::optional<VulkanLimit> limit_;
  std::shared_ptr<const gpu::ComputePipeline> output_;
  gpu::DescriptorSet output_set_;
  std::optional<gpu::GpuTimer> timer_;
  std::optional<gpu::Recording> frame_;
  std::optional<gpu::OutputReadback> readback_;
};

}  // namespace sdb::refined
