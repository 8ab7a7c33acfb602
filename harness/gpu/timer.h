// GpuTimer: timestamp queries around labelled passes of a command buffer, read back as the
// sdb::GpuTimes that schemes report (harness/core/gpu_times.h).
//
//   timer.reset(cmd);                                   // first, outside a render pass
//   timer.begin(cmd, PassKind::Upload, "upload"); cmd.upload(...); timer.end(cmd);
//   timer.begin(cmd, PassKind::Kernel, "subdivide"); ...dispatch...; timer.end(cmd);
//   timer.begin(cmd, PassKind::Readback, "readback"); cmd.download(...); timer.end(cmd);
//   ctx.submit(recording);   // waits
//   std::optional<GpuTimes> t = timer.read();
//
// Both timestamps of a pass are written at the bottom of the pipe, i.e. when every earlier
// command has finished: a pass's time runs from the end of the work before it to the end of its
// own, so consecutive passes add up to the whole without overlap. Passes do not nest. A pass
// begun right after another ended, with no work recorded in between, starts at that pass's end
// timestamp instead of writing its own: on lavapipe each timestamp costs a flush, and a pass
// with two measured ~0.06 ms more than its work (harness/gpu/README.md, "Timing").
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/gpu_times.h"
#include "harness/gpu/commands.h"
#include "harness/gpu/context.h"

namespace sdb::gpu {

enum class PassKind {
  Upload,    // counted in upload_ms
  Kernel,    // compute work, counted in kernel_ms
  Draw,      // rasterization, counted in kernel_ms
  Readback,  // counted in readback_ms
};

struct PassTimestamps {
  std::string label;
  PassKind kind = PassKind::Kernel;
  uint64_t begin_ticks = 0;  // raw timestamps, masked to the queue's valid bits
  uint64_t end_ticks = 0;
  double ms = 0.0;
};

class GpuTimer {
 public:
  explicit GpuTimer(Context& ctx, uint32_t max_passes = 64);
  ~GpuTimer();
  GpuTimer(GpuTimer&& other) noexcept;
  GpuTimer& operator=(GpuTimer&& other) noexcept;
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  // False when the queue family has no timestamps (timestampValidBits == 0); then the calls
  // below record nothing and read() gives nullopt.
  bool supported() const { return pool_ != VK_NULL_HANDLE; }

  void reset(Commands& cmd);
  // std::logic_error when a pass is open or more than max_passes were begun since reset().
  void begin(Commands& cmd, PassKind kind, std::string label);
  void end(Commands& cmd);

  // After the submission finished; nullopt when unsupported or the results are not there.
  std::optional<std::vector<PassTimestamps>> read_passes() const;
  std::optional<GpuTimes> read() const;

 private:
  void release();
  uint32_t write_timestamp(Commands& cmd);  // the query written

  Context* ctx_ = nullptr;
  VkQueryPool pool_ = VK_NULL_HANDLE;
  uint32_t max_passes_ = 0;
  struct Pass {
    std::string label;
    PassKind kind;
    uint32_t begin_query = 0, end_query = 0;
  };
  std::vector<Pass> passes_;
  bool open_ = false;
  uint32_t queries_ = 0;        // written since reset()
  VkCommandBuffer ended_in_ = VK_NULL_HANDLE;  // where the last pass ended,
  uint64_t work_at_end_ = 0;    // and the work recorded there by then
};

// Sums passes into upload_ms, kernel_ms (Kernel + Draw) and readback_ms, keeping every label.
GpuTimes to_gpu_times(const std::vector<PassTimestamps>& passes);

}  // namespace sdb::gpu
