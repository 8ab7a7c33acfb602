// gpu-check: a thin wrapper over harness/run/gpu_check.h, the report written by reports/.
#include <memory>

#include "harness/run/gpu_check.h"
#include "app/commands.h"
#include "reports/report.h"

namespace sdb::app {

void add_gpu_check_verbs(CLI::App& app, Verbs& verbs) {
  auto opts = std::make_shared<GpuCheckOptions>();
  auto* g = app.add_subcommand("gpu-check",
                               "The GPU check in stages (device facts; every GPU scheme at two output sizes of 10-60 M "
                               "triangles beside its CPU row, paired rounds; the render-mode paper tables): results.json, "
                               "the report and summary.txt, each stage journalled");
  g->add_option("--out", opts->out, "output folder (default results/gpu-check)");
  g->add_flag("--quick", opts->quick, "small outputs, one round, the paper tables' quick cells (any device)");
  g->add_flag("--allow-cpu-device", opts->allow_cpu_device,
              "run on a CPU implementation of Vulkan (lavapipe) too; its rates are labelled, never ranked as a GPU's");
  g->add_flag("--resume", opts->resume, "continue the check journalled in --out (gpu-check.jsonl): run only the stages it lacks");
  g->add_option("--rounds", opts->rounds, "paired rounds (default 3; 1 with --quick)")->check(CLI::PositiveNumber);
  g->add_option("--budget", opts->budget_s,
                "seconds for the stages (default 540): a stage still running then is stopped, later ones are left for --resume")
      ->check(CLI::PositiveNumber);
  g->add_flag("--plan", opts->plan_only, "print the stages and the runs of each, measure nothing");
  verbs["gpu-check"] = [opts] {
    return run_gpu_check(*opts, [](const std::string& results_json, const std::string& dir, const std::vector<std::string>& papers) {
      ReportOptions options;
      options.papers = papers;
      write_report({results_json}, dir, options);
    });
  };
}

}  // namespace sdb::app
