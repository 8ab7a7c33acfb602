// validate and run: one checked run, or a selection measured and written with its report.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "harness/bench/machine.h"
#include "harness/bench/measure.h"
#include "harness/bench/plan.h"
#include "harness/bench/results.h"
#include "harness/bench/row_worker.h"
#include "harness/bench/run_set.h"
#include "harness/cli/commands.h"
#include "harness/core/errors.h"
#include "reports/report.h"

namespace sdb::cli {
namespace {

struct RunOptions {
  std::vector<std::string> schemes, meshes, backends;
  std::vector<int> levels;
  std::string scheme, mesh, backend = "cpu", out = "results/latest", deviation_ply, resume;
  int level = 0, reps = 5;
  long rays = 50000;
  uint64_t seed = 1;
  bool json = false, all_meshes = false, all_corpus = false, no_validate = false, no_report = false;
  bool in_process = false;
  int worker_channel = -1;
  long worker_parent = 0;
};

void print_row(const RunRow& r) {
  std::printf("%-44s", r.name().c_str());
  if (r.status == RunStatus::Unsupported) {
    std::printf(" unsupported: %s\n", r.message.c_str());
    return;
  }
  std::printf(" %9ld tris %9.3f ms %8.2f Mtri/s bw %5.1f%%", r.triangles,
              r.gpu_time_ms ? r.gpu_time_ms->median : r.time_ms.median, r.triangle_rate_mtris, 100 * r.bandwidth_fraction);
  if (r.watertight.open_edges >= 0) std::printf("  open %ld", r.watertight.open_edges);
  if (r.watertight.ray_cracks >= 0) std::printf(" cracks %ld/%ld", r.watertight.ray_cracks, r.watertight.rays);
  if (r.deviation.measured)
    std::printf("  dev max %.3g%% p95 %.3g%% %.3gdeg", r.deviation.pos_max_pct, r.deviation.pos_p95_pct, r.deviation.normal_max_deg);
  const bool ok = r.status == RunStatus::Ok;
  std::printf("%s%s\n", ok ? "" : "  FAILED: ", ok ? "" : r.message.c_str());
}

MeasureOptions validate_options(const RunOptions& opts) {
  MeasureOptions m;
  m.reps = opts.reps;
  m.rays = opts.rays;
  m.seed = opts.seed;
  m.validate = !opts.no_validate;
  return m;
}

int validate(const RunOptions& opts) {
  auto backend = parse_backend(opts.backend);
  if (!backend) throw InputError(opts.backend, "no such backend (" + backend_names() + ")");
  MeasureContext ctx(describe_machine(is_gpu(*backend)));
  MeasureOptions m = validate_options(opts);
  m.time = false;
  m.deviation_ply = opts.deviation_ply;
  const RunSpec spec{opts.scheme, opts.mesh, *backend, opts.level};
  const RunRow row = measure_run(spec, m, ctx);
  // One explicit request the scheme declines is bad usage, not a result.
  if (row.status == RunStatus::Unsupported) throw InputError(spec.name(), row.message);
  if (opts.json) std::cout << row_json(row) << "\n";
  else print_row(row);
  return row.status == RunStatus::Failed ? 1 : 0;
}

void print_machine(const MachineInfo& m, size_t runs) {
  std::printf("%zu runs; machine: %s, %d cores, write bandwidth %.1f GB/s (1 thread), %.1f GB/s (all)", runs,
              m.cpu_model.c_str(), m.cores, m.write_bandwidth_gbs, m.write_bandwidth_mt_gbs);
  if (!m.vulkan_device.empty()) std::printf(", %s %.2f GB/s", m.vulkan_device.c_str(), m.gpu_write_bandwidth_gbs);
  if (!m.opengl_renderer.empty()) std::printf(", OpenGL: %s", m.opengl_renderer.c_str());
  std::printf("\n");
}

RunSelection run_selection(const RunOptions& opts) {
  RunSelection r;
  Selection& sel = r.selection;
  sel.schemes = opts.schemes, sel.meshes = opts.meshes, sel.backends = opts.backends, sel.levels = opts.levels;
  sel.all_meshes = opts.all_meshes || opts.all_corpus;
  sel.all_corpus = opts.all_corpus;
  r.reps = opts.reps, r.rays = opts.rays, r.seed = opts.seed, r.validate = !opts.no_validate;
  return r;
}

// `selection_given`: with --resume, whether the command line named a selection of its own (it
// must then be the journalled one) or leaves it to the journal.
int run(const RunOptions& opts, bool selection_given) {
  const bool isolate = !opts.in_process;
  RunSet set = opts.resume.empty()
                   ? RunSet::start(opts.out, run_selection(opts), isolate)
                   : RunSet::resume(opts.resume, selection_given ? std::optional(run_selection(opts)) : std::nullopt, isolate);
  const std::string out = opts.resume.empty() ? opts.out : opts.resume;
  for (const auto& n : set.plan().notes) std::printf("note: %s\n", n.c_str());
  if (set.plan().runs.empty()) {
    std::printf("nothing to run for this selection; nothing written\n");
    return 0;
  }
  print_machine(set.machine(), set.plan().runs.size());
  if (!opts.resume.empty())
    std::printf("resuming %s: %zu of %zu rows journalled%s; measuring %zu\n", out.c_str(), set.journalled(),
                set.plan().runs.size(), set.dropped_torn_line() ? " (a torn last line dropped)" : "", set.remaining());
  set.measure_remaining(print_row);
  RunSet::ReportWriter report;
  if (!opts.no_report) report = [](const std::string& results, const std::string& dir) { write_report({results}, dir); };
  const ResultsFile results = set.publish(report);
  std::printf("wrote %s\n", (std::filesystem::path(out) / "results.json").string().c_str());
  const bool failed = std::any_of(results.runs.begin(), results.runs.end(), [](const RunRow& r) { return r.status == RunStatus::Failed; });
  return failed ? 1 : 0;
}

void add_selection(CLI::App* cmd, RunOptions& opts) {
  cmd->add_option("--scheme", opts.schemes,
                  "scheme name, with parameters as name:key=value[,key=value] (repeatable; default: all)");
  cmd->add_option("--mesh", opts.meshes, "mesh name or path (repeatable; default: the curated set, see README)");
  cmd->add_option("--backend", opts.backends, "cpu | cpu-mt | vulkan | opengl (repeatable; default: all available)");
  cmd->add_option("--level", opts.levels, "depth k or rate N (repeatable; default: the scheme's levels)");
  cmd->add_flag("--all", opts.all_meshes, "every built-in and every real corpus mesh instead of the curated set");
  cmd->add_flag("--all-corpus", opts.all_corpus, "--all, and OpenSubdiv's regression shapes too");
}

}  // namespace

void add_run_verbs(CLI::App& app, Verbs& verbs) {
  auto opts = std::make_shared<RunOptions>();
  auto* v = app.add_subcommand("validate", "Watertightness and deviation of one run, printed as a results row");
  v->add_option("--scheme", opts->scheme, "scheme, with parameters as name:key=value[,key=value]")->required();
  v->add_option("--mesh", opts->mesh, "mesh name or path")->required();
  v->add_option("--level", opts->level, "depth k or rate N")->required();
  v->add_option("--backend", opts->backend, "cpu | cpu-mt | vulkan | opengl");
  v->add_option("--rays", opts->rays, "random lines (as many again aimed at patch borders)")->check(CLI::NonNegativeNumber);
  v->add_option("--seed", opts->seed, "seed of the ray generator");
  v->add_flag("--json", opts->json, "print the row as JSON (results.json row format)");
  v->add_option("--deviation-out", opts->deviation_ply, "write the output with per-vertex deviation as a PLY file");
  verbs["validate"] = [opts] { return validate(*opts); };

  auto* r = app.add_subcommand("run", "Run, validate and time schemes; write results.json and the report");
  add_selection(r, *opts);
  r->add_option("--reps", opts->reps, "timed repetitions per run")->check(CLI::PositiveNumber);
  r->add_option("--rays", opts->rays, "random lines per run, as many again aimed at patch borders (default 50000)")
      ->check(CLI::NonNegativeNumber);
  r->add_flag("--no-validate", opts->no_validate, "time only");
  // What a resumed run compares with its journal: given at all, the whole selection must match.
  std::vector<const CLI::Option*> selection;
  for (const char* name : {"--scheme", "--mesh", "--backend", "--level", "--all", "--all-corpus", "--reps", "--rays", "--no-validate"})
    selection.push_back(r->get_option(name));
  auto* out = r->add_option("--out", opts->out, "output folder (results.json, report, journal.jsonl)");
  r->add_option("--resume", opts->resume,
                "continue the interrupted run journalled in DIR (DIR/journal.jsonl): measure only the rows it lacks")
      ->excludes(out);
  r->add_flag("--no-report", opts->no_report, "write results.json only");
  r->add_flag("--in-process", opts->in_process,
              "measure every row in this process, for profilers and debuggers (default: in a worker process, "
              "so that a crash in a library fails its row and the run goes on)");
  verbs["run"] = [opts, selection] {
    const bool given = std::any_of(selection.begin(), selection.end(), [](const CLI::Option* o) { return o->count() > 0; });
    return run(*opts, given);
  };

  auto* w = app.add_subcommand("row-worker", "");  // hidden: measures run's rows in a worker process (row_worker.h)
  w->group("");
  w->add_option("--channel-fd", opts->worker_channel)->required();
  w->add_option("--parent", opts->worker_parent)->required();
  verbs["row-worker"] = [opts]() -> int { serve_rows(opts->worker_channel, opts->worker_parent); };
}

}  // namespace sdb::cli
