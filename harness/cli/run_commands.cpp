#include "run_commands.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iostream>

#include "errors.h"
#include "machine.h"
#include "measure.h"
#include "plan.h"
#include "registry.h"
#include "report.h"
#include "results.h"

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
RunOptions o;

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

void print_row(const RunRow& r) {
  std::printf("%-44s", (r.scheme + "/" + r.backend + "/" + r.mesh + "/" + std::to_string(r.level)).c_str());
  if (r.status == "unsupported") {
    std::printf(" unsupported: %s\n", r.message.c_str());
    return;
  }
  std::printf(" %9ld tris %9.3f ms %8.2f Mtri/s bw %5.1f%%", r.triangles,
              r.gpu_time_ms ? r.gpu_time_ms->median : r.time_ms.median, r.triangle_rate_mtris, 100 * r.bandwidth_fraction);
  if (r.watertight.open_edges >= 0) std::printf("  open %ld", r.watertight.open_edges);
  if (r.watertight.ray_cracks >= 0) std::printf(" cracks %ld/%ld", r.watertight.ray_cracks, r.watertight.rays);
  if (r.deviation.measured)
    std::printf("  dev max %.3g%% p95 %.3g%% %.3gdeg", r.deviation.pos_max_pct, r.deviation.pos_p95_pct, r.deviation.normal_max_deg);
  std::printf("%s%s\n", r.status == "ok" ? "" : "  FAILED: ", r.status == "ok" ? "" : r.message.c_str());
}

MeasureOptions measure_options() {
  MeasureOptions m;
  m.reps = o.reps;
  m.rays = o.rays;
  m.seed = o.seed;
  m.validate = !o.no_validate;
  return m;
}

int validate() {
  MeasureContext ctx(describe_machine());
  auto backend = parse_backend(o.backend);
  if (!backend) throw InputError(o.backend, "no such backend (cpu, cpu-mt, vulkan)");
  MeasureOptions m = measure_options();
  m.time = false;
  m.deviation_ply = o.deviation_ply;
  const RunSpec spec{o.scheme, o.mesh, *backend, o.level};
  const RunRow row = measure_run(spec, m, ctx);
  // One explicit request the scheme declines is bad usage, not a result.
  if (row.status == "unsupported") throw InputError(spec.name(), row.message);
  if (o.json) std::cout << row_json(row) << "\n";
  else print_row(row);
  return row.status == "failed" ? 1 : 0;
}

int run() {
  MeasureContext ctx(describe_machine_with_probes());
  Selection sel;
  sel.schemes = o.schemes, sel.meshes = o.meshes, sel.backends = o.backends, sel.levels = o.levels;
  sel.all_meshes = o.all_meshes || o.all_corpus;
  sel.all_corpus = o.all_corpus;
  const Plan plan = make_plan(sel, ctx);
  for (const auto& n : plan.notes) std::printf("note: %s\n", n.c_str());
  if (plan.runs.empty()) {
    std::printf("nothing to run for this selection; nothing written\n");
    return 0;
  }
  ResultsFile results;
  results.machine = ctx.machine();
  results.created = utc_now();
  std::printf("%zu runs; machine: %s, %d cores, write bandwidth %.1f GB/s (1 thread), %.1f GB/s (all)%s\n",
              plan.runs.size(), results.machine.cpu_model.c_str(), results.machine.cores,
              results.machine.write_bandwidth_gbs, results.machine.write_bandwidth_mt_gbs,
              results.machine.vulkan_device.empty() ? ""
                  : (", " + results.machine.vulkan_device + " " + std::to_string(results.machine.gpu_write_bandwidth_gbs).substr(0, 5) + " GB/s").c_str());
  bool failed = false;
  MeasureOptions options = measure_options();
  options.refusals_as_rows = !(o.schemes.size() == 1 && o.meshes.size() == 1);
  for (const RunSpec& spec : plan.runs) {
    results.runs.push_back(measure_run(spec, options, ctx));
    print_row(results.runs.back());
    failed |= results.runs.back().status == "failed";
  }
  std::filesystem::create_directories(o.out);
  const std::string json_path = (std::filesystem::path(o.out) / "results.json").string();
  write_results(results, json_path);
  std::printf("wrote %s\n", json_path.c_str());
  if (!o.no_report) write_report({json_path}, o.out);
  return failed ? 1 : 0;
}

void add_selection(CLI::App* cmd) {
  cmd->add_option("--scheme", o.schemes, "scheme name (repeatable; default: all)");
  cmd->add_option("--mesh", o.meshes, "mesh name or path (repeatable; default: the curated set, see README)");
  cmd->add_option("--backend", o.backends, "cpu | cpu-mt | vulkan (repeatable; default: all available)");
  cmd->add_option("--level", o.levels, "depth k or rate N (repeatable; default: the scheme's levels)");
  cmd->add_flag("--all", o.all_meshes, "every built-in and every real corpus mesh instead of the curated set");
  cmd->add_flag("--all-corpus", o.all_corpus, "--all, and OpenSubdiv's regression shapes too");
}

}  // namespace

void register_run_commands(CLI::App& app, std::map<std::string, std::function<int()>>& verbs) {
  auto* v = app.add_subcommand("validate", "Watertightness and deviation of one run, printed as a results row");
  v->add_option("--scheme", o.scheme, "scheme")->required();
  v->add_option("--mesh", o.mesh, "mesh name or path")->required();
  v->add_option("--level", o.level, "depth k or rate N")->required();
  v->add_option("--backend", o.backend, "cpu | cpu-mt | vulkan");
  v->add_option("--rays", o.rays, "random lines (as many again aimed at patch borders)");
  v->add_option("--seed", o.seed, "seed of the ray generator");
  v->add_flag("--json", o.json, "print the row as JSON (results.json row format)");
  v->add_option("--deviation-out", o.deviation_ply, "write the output with per-vertex deviation as a PLY file");
  verbs["validate"] = validate;

  auto* r = app.add_subcommand("run", "Run, validate and time schemes; write results.json and the report");
  add_selection(r);
  r->add_option("--reps", o.reps, "timed repetitions per run");
  r->add_option("--rays", o.rays, "random lines per run, as many again aimed at patch borders (default 50000)");
  r->add_option("--out", o.out, "output folder");
  r->add_flag("--no-validate", o.no_validate, "time only");
  r->add_flag("--no-report", o.no_report, "write results.json only");
  verbs["run"] = run;
}

}  // namespace sdb::cli
