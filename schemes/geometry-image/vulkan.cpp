// The vulkan evaluation: the VulkanSubdivider on the process's shared context. execute() uploads
// g0 and runs the passes (timed by timestamps); result() reads p^k and n^k back, a separately
// timed submission, as the paper's timings stop before rendering (its RENDER_TO_VERTEX kept the
// vertices on the GPU; ours stay in device buffers made for vertex use as well).
#include "harness/core/errors.h"
#include "harness/gpu/gpu.h"
#include "schemes/geometry-image/backends.h"
#include "schemes/geometry-image/tessellation_grid.h"
#include "schemes/geometry-image/vulkan_subdivider.h"

namespace sdb::gim {

namespace {

class VulkanEvaluation final : public Evaluation {
 public:
  VulkanEvaluation(const EvaluationInput& in, std::shared_ptr<gpu::Context> ctx)
      : ctx_(std::move(ctx)), g0_(in.g0), subdivider_(*ctx_, in.base_size, in.request.level, in.plan) {
    out_ = grid_tessellation(in.base_size, in.request.level, subdivider_.size(in.request.level), g0_);
  }

  void execute() override {
    subdivider_.run(g0_->positions.data());
    stale_ = true;
  }
  const Tessellation& result() override {
    if (stale_) subdivider_.read_back(out_.positions.data(), out_.normals.data());
    stale_ = false;
    return out_;
  }
  size_t bytes_out() const override { return out_.positions.size() * 2 * sizeof(Point3); }
  std::optional<GpuTimes> gpu_times() const override { return subdivider_.times(); }

 private:
  std::shared_ptr<gpu::Context> ctx_;  // outlives the subdivider's Vulkan objects
  std::shared_ptr<const ControlMesh> g0_;
  VulkanSubdivider subdivider_;
  Tessellation out_;
  bool stale_ = false;  // executed since the last readback
};

}  // namespace

std::unique_ptr<Evaluation> make_vulkan_evaluation(const EvaluationInput& input, const std::string& mesh_name) {
  std::shared_ptr<gpu::Context> ctx = gpu::shared_context();
  if (auto why = VulkanSubdivider::unsupported(*ctx, input.base_size, input.request.level, input.plan))
    throw Unsupported(mesh_name + ": " + *why);
  return std::make_unique<VulkanEvaluation>(input, std::move(ctx));
}

std::optional<std::string> vulkan_unavailable() {
  static const gpu::DeviceInfo device = gpu::probe();
  if (device.available) return std::nullopt;
  return "no Vulkan device: " + device.reason;
}

}  // namespace sdb::gim
