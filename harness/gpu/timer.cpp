#include "harness/gpu/timer.h"

#include <stdexcept>
#include <utility>

#include "harness/gpu/errors.h"

namespace sdb::gpu {

GpuTimer::GpuTimer(Context& ctx, uint32_t max_passes) : ctx_(&ctx), max_passes_(max_passes) {
  if (ctx.limits().timestamp_valid_bits == 0) return;
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = 2 * max_passes;
  check(ctx.vk().vkCreateQueryPool(ctx.device(), &info, nullptr, &pool_), "vkCreateQueryPool",
        "creating the timestamp query pool");
}

GpuTimer::~GpuTimer() { release(); }

GpuTimer::GpuTimer(GpuTimer&& other) noexcept { *this = std::move(other); }

GpuTimer& GpuTimer::operator=(GpuTimer&& other) noexcept {
  if (this != &other) {
    release();
    ctx_ = std::exchange(other.ctx_, nullptr);
    pool_ = std::exchange(other.pool_, VK_NULL_HANDLE);
    max_passes_ = other.max_passes_;
    passes_ = std::move(other.passes_);
    open_ = std::exchange(other.open_, false);
    queries_ = std::exchange(other.queries_, 0);
    ended_in_ = std::exchange(other.ended_in_, VK_NULL_HANDLE);
    work_at_end_ = other.work_at_end_;
  }
  return *this;
}

void GpuTimer::release() {
  if (ctx_ && pool_) ctx_->vk().vkDestroyQueryPool(ctx_->device(), pool_, nullptr);
  pool_ = VK_NULL_HANDLE;
  ctx_ = nullptr;
}

void GpuTimer::reset(Commands& cmd) {
  passes_.clear();
  open_ = false;
  queries_ = 0;
  ended_in_ = VK_NULL_HANDLE;
  if (pool_) ctx_->vk().vkCmdResetQueryPool(cmd.raw(), pool_, 0, 2 * max_passes_);
}

void GpuTimer::begin(Commands& cmd, PassKind kind, std::string label) {
  if (open_) throw std::logic_error("GpuTimer: pass '" + label + "' begun inside pass '" + passes_.back().label + "'");
  if (passes_.size() >= max_passes_)
    throw std::logic_error("GpuTimer: more than " + std::to_string(max_passes_) +
                           " passes since reset(); make the timer with a larger max_passes");
  const bool follows = !passes_.empty() && ended_in_ == cmd.raw() && work_at_end_ == cmd.work_recorded();
  const uint32_t begin = follows ? passes_.back().end_query : write_timestamp(cmd);
  passes_.push_back({std::move(label), kind, begin, 0});
  open_ = true;
}

void GpuTimer::end(Commands& cmd) {
  if (!open_) throw std::logic_error("GpuTimer: end() without begin()");
  open_ = false;
  passes_.back().end_query = write_timestamp(cmd);
  ended_in_ = cmd.raw();
  work_at_end_ = cmd.work_recorded();
}

uint32_t GpuTimer::write_timestamp(Commands& cmd) {
  const uint32_t query = queries_++;
  if (!pool_) return query;
  ctx_->vk().vkCmdWriteTimestamp(cmd.raw(), VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, query);
  // Lavapipe takes the time of a timestamp only at its next flush, which a barrier forces; without
  // it a pass's compute work lands in the next pass. Elsewhere it only keeps passes from overlapping.
  if (!cmd.inside_render_pass()) cmd.execution_barrier();
  return query;
}

std::optional<std::vector<PassTimestamps>> GpuTimer::read_passes() const {
  if (!pool_ || open_) return std::nullopt;
  std::vector<PassTimestamps> out;
  if (passes_.empty()) return out;
  std::vector<uint64_t> ticks(queries_);
  const VkResult r = ctx_->vk().vkGetQueryPoolResults(ctx_->device(), pool_, 0, static_cast<uint32_t>(ticks.size()),
                                                      ticks.size() * sizeof(uint64_t), ticks.data(), sizeof(uint64_t),
                                                      VK_QUERY_RESULT_64_BIT);
  if (r == VK_NOT_READY) return std::nullopt;
  check(r, "vkGetQueryPoolResults", "reading timestamps");
  const uint32_t bits = ctx_->limits().timestamp_valid_bits;
  const uint64_t mask = bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << bits) - 1;
  const double ms_per_tick = double(ctx_->limits().timestamp_period_ns) * 1e-6;
  for (size_t i = 0; i < passes_.size(); ++i) {
    PassTimestamps p;
    p.label = passes_[i].label;
    p.kind = passes_[i].kind;
    p.begin_ticks = ticks[passes_[i].begin_query] & mask;
    p.end_ticks = ticks[passes_[i].end_query] & mask;
    // Modular difference: a counter with fewer than 64 valid bits may wrap inside a pass.
    p.ms = double((p.end_ticks - p.begin_ticks) & mask) * ms_per_tick;
    out.push_back(std::move(p));
  }
  return out;
}

std::optional<GpuTimes> GpuTimer::read() const {
  auto passes = read_passes();
  if (!passes) return std::nullopt;
  return to_gpu_times(*passes);
}

GpuTimes to_gpu_times(const std::vector<PassTimestamps>& passes) {
  GpuTimes times;
  for (const PassTimestamps& p : passes) {
    switch (p.kind) {
      case PassKind::Upload: times.upload_ms += p.ms; break;
      case PassKind::Kernel:
      case PassKind::Draw: times.kernel_ms += p.ms; break;
      case PassKind::Readback: times.readback_ms += p.ms; break;
    }
    times.passes.push_back({p.label, p.ms});
  }
  return times;
}

}  // namespace sdb::gpu
