// Vulkan timestamp figures of one evaluation, as schemes report them and results rows record them.
#pragma once

#include <string>
#include <vector>

namespace sdb {

struct GpuPassTime {
  std::string label;
  double ms = 0.0;
};

struct GpuTimes {
  double upload_ms = 0.0;
  double kernel_ms = 0.0;  // sum of the compute / draw passes
  double readback_ms = 0.0;
  std::vector<GpuPassTime> passes;
};

}  // namespace sdb
