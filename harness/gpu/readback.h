// The positions and normals a frame leaves in two device buffers, read back into a Tessellation
// when its result is asked for (outside the timed frame), under a timestamp pair of its own
// ("readback"). What every scheme whose Vulkan output is one positions and one normals buffer
// repeated (fragments, mipgh).
#pragma once

#include <optional>
#include <vector>

#include "harness/core/tessellation.h"
#include "harness/gpu/buffer.h"
#include "harness/gpu/commands.h"
#include "harness/gpu/timer.h"

namespace sdb::gpu {

class OutputReadback {
 public:
  // `positions` and `normals` hold `bytes` each and outlive this.
  OutputReadback(Context& ctx, const Buffer& positions, const Buffer& normals, uint64_t bytes);
  // After each frame: the next read_into reads the device again.
  void invalidate() { stale_ = true; }
  // Reads both buffers into out's positions and normals (sized by the caller), once per frame.
  void read_into(Tessellation& out);
  // The last readback's pass, after a frame's passes, where one was read.
  void append_passes(std::vector<PassTimestamps>& passes) const;

 private:
  Context* ctx_;
  Buffer positions_staging_, normals_staging_;
  std::optional<GpuTimer> timer_;
  std::optional<Recording> recording_;
  bool stale_ = false, read_ = false;
};

}  // namespace sdb::gpu
