#include "harness/refined/vulkan_frame.h"

#include <algorithm>

#include "sdb_refined_shaders.h"

namespace sdb::refined {
namespace {

struct OutputPush {  // shaders/points_out.comp
  uint32_t count = 0, pad[3] = {0, 0, 0};
  float origin[4] = {0, 0, 0, 0};
};

}  // namespace

VulkanFrame::VulkanFrame(std::shared_ptr<gpu::Context> ctx, std::vector<Point3> control, std::vector<uint32_t> order,
                         const float origin[3], Tessellation& out)
    : ctx_(std::move(ctx)),
      control_(std::move(control)),
      order_(std::move(order)),
      origin_{origin[0], origin[1], origin[2]},
      out_(&out),
      out_vertices_(static_cast<uint32_t>(out.positions.size())),
      relative_(order_.empty() ? control_.size() : order_.size()) {}

void VulkanFrame::check_device(uint64_t scheme_bytes, const LimitPlan* plan, const std::string& what) {
  output_bytes_ = std::max<uint64_t>(12 * uint64_t(out_vertices_), 16);
  gpu::check_texel_binding(*ctx_, 3 * uint64_t(out_vertices_), "the output's floats");
  uint64_t device = scheme_bytes + 2 * output_bytes_;
  if (plan) device += VulkanLimit::table_bytes(*plan);
  gpu::check_memory(*ctx_, {device, 2 * output_bytes_ + 16 * uint64_t(uploaded())}, what);
}

void VulkanFrame::make_output_buffers() {
  staging_ = gpu::Buffer::upload(*ctx_, std::max<uint64_t>(16 * uint64_t(uploaded()), 16), "control points (staging)");
  const gpu::BufferUsage out = gpu::BufferUsage::StorageTexel | gpu::BufferUsage::Storage;
  positions_ = gpu::Buffer::device(*ctx_, output_bytes_, out, "positions");
  normals_ = gpu::Buffer::device(*ctx_, output_bytes_, out, "normals");
}

void VulkanFrame::bind_output(const LimitPlan* plan, const gpu::Buffer& points, const gpu::Buffer& early_points) {
  if (plan) {
    limit_.emplace(*ctx_, *plan);
    limit_->bind(points, early_points, positions_, normals_);
    return;
  }
  using gpu::Binding;
  output_ = gpu::shared_compute_pipeline(*ctx_, {sdb_refined_shaders::get("points_out.comp"),
                                                 {Binding::UniformTexelBuffer, Binding::StorageTexelBuffer},
                                                 sizeof(OutputPush),
                                                 {{0, kLocalSize}}});
  output_set_ = gpu::DescriptorSet(*output_, {points.texels(kPoint), positions_.texels(kFloat)});
}

void VulkanFrame::record_frame(const gpu::Buffer& upload_to, uint32_t max_passes,
                               const std::function<void(gpu::Commands&, gpu::GpuTimer&)>& passes) {
  timer_.emplace(*ctx_, max_passes + 3);  // and the upload and the tail's two
  frame_ = ctx_->record([&](gpu::Commands& cmd) {
    timer_->reset(cmd);
    timer_->begin(cmd, gpu::PassKind::Upload, "upload");
    cmd.upload(staging_, upload_to, 16 * uint64_t(uploaded()));
    timer_->end(cmd);
    passes(cmd, *timer_);
    if (limit_) {
      limit_->record(cmd, *timer_, origin_);
      return;
    }
    OutputPush p;
    p.count = out_vertices_;
    for (int k = 0; k < 3; ++k) p.origin[k] = origin_[k];
    timer_->begin(cmd, gpu::PassKind::Kernel, "output");
    cmd.bind(*output_, output_set_);
    cmd.push(p);
    cmd.dispatch(gpu::groups_for(p.count, kLocalSize, ctx_->limits()));
    timer_->end(cmd);
  });
  readback_.emplace(*ctx_, positions_, normals_, output_bytes_);
}

void VulkanFrame::execute() {
  for (size_t i = 0; i < relative_.size(); ++i) {
    const Point3& p = control_[order_.empty() ? i : order_[i]];
    relative_[i] = {p[0] - origin_[0], p[1] - origin_[1], p[2] - origin_[2], 0.0f};
  }
  staging_.write(relative_);
  ctx_->submit(*frame_);
  readback_->invalidate();
}

const Tessellation& VulkanFrame::result() {
  readback_->read_into(*out_);
  return *out_;
}

std::optional<GpuTimes> VulkanFrame::gpu_times() const {
  auto passes = timer_->read_passes();
  if (!passes) return std::nullopt;
  readback_->append_passes(*passes);
  return gpu::to_gpu_times(*passes);
}

}  // namespace sdb::refined
