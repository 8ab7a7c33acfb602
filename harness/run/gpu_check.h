// `subdivbench gpu-check`: the check a GPU machine gets (scripts/gpu-check, a GPU bundle's `run`),
// in stages ordered so that a run cut off at any point leaves what it measured:
//   1. device facts: the Vulkan and OpenGL devices, device memory, the write-bandwidth probes;
//   2. every GPU scheme of the registry at one output size (gpu_check_plan.h), evaluate-only, in
//      paired rounds beside the CPU row of the same output, one `bench` child process per scheme;
//   3. the same at a second size;
//   4. the render-mode paper tables (ni2008-table4, shiue-loop-table1), one `paper` child each.
// Each finished stage is appended to DIR/gpu-check.jsonl (a line file, fsync'ed) and results.json
// and summary.txt are rewritten from the stages so far; a kill loses at most the stage in flight,
// and `--resume` runs only the stages the journal lacks. At the end the report. A budget ends the
// check in time (the device facts are always taken): a child still running when it is spent is
// stopped and its stage marked cut off, later stages are left for --resume.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace sdb {

inline constexpr const char* kGpuCheckJournal = "gpu-check.jsonl";
inline constexpr const char* kGpuCheckSummary = "summary.txt";

struct GpuCheckOptions {
  std::string out = "results/gpu-check";
  bool quick = false;             // small outputs, one round, the paper tables' quick cells
  bool allow_cpu_device = false;  // run on a CPU implementation of Vulkan (lavapipe) too
  bool resume = false;            // continue the check journalled in `out`
  int rounds = 0;                 // paired rounds; 0: 3 (1 with quick)
  double budget_s = 540;          // seconds for the stages (the report comes after)
  bool plan_only = false;         // print the stages and their runs, measure nothing
};

// Prints the stages as they run and the summary at the end; returns the exit code: 0 when every
// stage ran and the report was written (or there is no Vulkan device to check: said, nothing
// written), 1 when a stage failed, was cut off or not reached, or the report could not be written.
// InputError (exit 2) for a journal that cannot be resumed.
// `report` writes the report of `results_json` with the paper tables' Markdown into `dir` (the CLI
// passes reports/'s write_report); what it throws is said in the summary, the results stay.
using CheckReportWriter =
    std::function<void(const std::string& results_json, const std::string& dir, const std::vector<std::string>& papers)>;
int run_gpu_check(const GpuCheckOptions& options, const CheckReportWriter& report);

}  // namespace sdb
