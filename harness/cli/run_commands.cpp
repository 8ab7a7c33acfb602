// validate and run: one checked run, or a selection measured and written with its report.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <memory>

#include "harness/bench/machine.h"
#include "harness/bench/measure.h"
#include "harness/bench/plan.h"
#include "harness/bench/results.h"
#include "harness/cli/commands.h"
#include "harness/core/errors.h"
#include "reports/report.h"

namespace sdb::cli {
namespace {

struct RunOptions {
  std::vector<std::string> schemes, meshes, backends;
  std::vector<int> levels;
  std::string scheme, mesh, backend = "cpu", out = "results/latest", deviation_ply;
  int level = 0, reps = 5;
  long rays = 50000;
  uint64_t seed = 1;
  bool json = false, all_meshes = false, all_corpus = false, no_validate = false, no_report = false;
};

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

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

MeasureOptions measure_options(const RunOptions& opts) {
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
  MeasureOptions m = measure_options(opts);
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

void print_machine(const ResultsFile& results, size_t runs) {
  const MachineInfo& m = results.machine;
  std::printf("%zu runs; machine: %s, %d cores, write bandwidth %.1f GB/s (1 thread), %.1f GB/s (all)", runs,
              m.cpu_model.c_str(), m.cores, m.write_bandwidth_gbs, m.write_bandwidth_mt_gbs);
  if (!m.vulkan_device.empty()) std::printf(", %s %.2f GB/s", m.vulkan_device.c_str(), m.gpu_write_bandwidth_gbs);
  if (!m.opengl_renderer.empty()) std::printf(", OpenGL: %s", m.opengl_renderer.c_str());
  std::printf("\n");
}

// Nothing ran (every row unsupported): said, and exit 2, and no earlier results replaced.
void require_something_ran(const ResultsFile& results) {
  for (const RunRow& r : results.runs)
    if (r.status != RunStatus::Unsupported) return;
  throw InputError("run", "nothing ran: all " + std::to_string(results.runs.size()) + " runs unsupported (" +
                              (results.runs.empty() ? std::string() : results.runs.front().message) + "); nothing written");
}

int run(const RunOptions& opts) {
  prepare_output_folder(opts.out);  // before the measuring, not after it
  MeasureContext ctx(describe_machine_with_probes());
  Selection sel;
  sel.schemes = opts.schemes, sel.meshes = opts.meshes, sel.backends = opts.backends, sel.levels = opts.levels;
  sel.all_meshes = opts.all_meshes || opts.all_corpus;
  sel.all_corpus = opts.all_corpus;
  const Plan plan = make_plan(sel, ctx);
  for (const auto& n : plan.notes) std::printf("note: %s\n", n.c_str());
  if (plan.runs.empty()) {
    std::printf("nothing to run for this selection; nothing written\n");
    return 0;
  }
  ResultsFile results;
  results.machine = ctx.machine();
  results.created = utc_now();
  print_machine(results, plan.runs.size());
  bool failed = false;
  MeasureOptions options = measure_options(opts);
  options.refusals_as_rows = !(opts.schemes.size() == 1 && opts.meshes.size() == 1);
  for (const RunSpec& spec : plan.runs) {
    results.runs.push_back(measure_run(spec, options, ctx));
    print_row(results.runs.back());
    failed |= results.runs.back().status == RunStatus::Failed;
  }
  require_something_ran(results);
  const std::string json_path = (std::filesystem::path(opts.out) / "results.json").string();
  write_results(results, json_path);
  std::printf("wrote %s\n", json_path.c_str());
  if (!opts.no_report) write_report({json_path}, opts.out);
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
  r->add_option("--out", opts->out, "output folder");
  r->add_flag("--no-validate", opts->no_validate, "time only");
  r->add_flag("--no-report", opts->no_report, "write results.json only");
  verbs["run"] = [opts] { return run(*opts); };
}

}  // namespace sdb::cli
