// The GPU check's one-screen summary (summary.txt, and the last lines `gpu-check` prints): the
// device, the best GPU rate of each scheme with its fraction of the device's write bandwidth and its
// paired ratio to the CPU row beside it, and what did not run. Rows on a CPU implementation of
// Vulkan or OpenGL (lavapipe, llvmpipe) are marked as such and never ranked as a GPU's.
#pragma once

#include <string>
#include <vector>

#include "harness/results/results.h"

namespace sdb {

struct CheckProgress {
  size_t stages = 0;  // planned
  size_t ok = 0, failed = 0, cut_off = 0, not_run = 0;
  std::vector<std::string> problems;  // "size 2: mipgh-cc: exit code 3 (...)", one per failed or cut-off stage
  std::vector<std::string> notes;     // the plan's: schemes left out or at one size only, and why
  double budget_s = 0;
  std::string report;  // "" when the report was written, else why not; "pending" before the end
};

inline constexpr double kGpuRateTargetMtris = 5000;  // the target: >= 5 G triangles/s evaluate-only

// About a dozen lines and one per scheme, none wider than 100 characters.
std::vector<std::string> gpu_check_summary(const ResultsFile& results, const CheckProgress& progress);

}  // namespace sdb
