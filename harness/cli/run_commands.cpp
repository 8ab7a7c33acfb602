// validate and run: one checked run, or a selection measured and written with its report.
#include <cmath>
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>

#include "harness/bench/machine.h"
#include "harness/bench/measure.h"
#include "harness/bench/paired.h"
#include "harness/run/plan.h"
#include "harness/bench/progress.h"
#include "harness/run/row_worker.h"
#include "harness/run/run_set.h"
#include "harness/run/run_summary.h"
#include "harness/cli/commands.h"
#include "harness/core/errors.h"
#include "harness/core/printable.h"
#include "harness/core/registry.h"
#include "harness/gpu/context.h"
#include "harness/pictures/pictures.h"
#include "harness/results/results.h"
#include "reports/report.h"

namespace sdb::cli {
namespace {

constexpr int kQuickReps = 3, kQuickRounds = 3;
constexpr long kQuickRays = 10000;
// Each benchmark's time in a paired round: long enough to average a few executions of the small
// rows, short enough that a default run's cells cost seconds, not minutes.
constexpr double kPairedMinTime = 0.03;


struct RunOptions {
  std::vector<std::string> schemes, meshes, backends;
  std::vector<int> levels;
  std::string scheme, mesh, backend = "cpu", out = "results/latest", deviation_ply, resume;
  int level = 0, reps = 5;
  long rays = 50000;
  uint64_t seed = 1;
  bool json = false, all_meshes = false, all_corpus = false, no_validate = false, no_report = false;
  bool in_process = false, force = false;
  bool quick = false, full = false, no_paired = false, no_pictures = false, no_papers = false;
  bool plan_only = false;  // --plan
  std::string shard;  // "I/N"
  int rounds = 5;     // paired rounds of the summary cells
  bool rounds_given = false;
  int worker_channel = -1;
  long worker_parent = 0;
};

// The row's name padded to a column, and its figures.
std::string row_head(const RunRow& r) {
  std::string head = printable(r.name());
  head.resize(std::max<size_t>(head.size(), 44), ' ');
  return head;
}

std::string row_figures(const RunRow& r) {
  char buf[512];
  std::string line;
  if (r.status == RunStatus::Unsupported) return " unsupported: " + printable(r.message);
  std::snprintf(buf, sizeof buf, " %9ld tris %9.3f ms %8.2f Mtri/s bw %5.1f%%", r.triangles,
                r.gpu_time_ms ? r.gpu_time_ms->median : r.time_ms.median, r.triangle_rate_mtris, 100 * r.bandwidth_fraction);
  line += buf;
  if (r.watertight.open_edges >= 0) line += "  open " + std::to_string(r.watertight.open_edges);
  if (r.watertight.ray_cracks >= 0)
    line += " cracks " + std::to_string(r.watertight.ray_cracks) + "/" + std::to_string(r.watertight.rays);
  if (r.deviation.measured) {
    std::snprintf(buf, sizeof buf, "  dev max %.3g%% p95 %.3g%%", r.deviation.pos_max_pct, r.deviation.pos_p95_pct);
    line += buf;
    // NaN: no normal compared (a scheme that outputs none, mipgh-quadtri's nodes).
    if (std::isnan(r.deviation.normal_max_deg)) {
      line += " no normals";
    } else {
      std::snprintf(buf, sizeof buf, " %.3gdeg", r.deviation.normal_max_deg);
      line += buf;
    }
    if (r.limit == "approximates") {
      std::snprintf(buf, sizeof buf, "  approximates%s: max %.2g p95 %.2g of the diagonal",
                    r.deviation.measured_by == "nearest-point" ? " (nearest points)" : "", r.deviation.pos_max_rel_diag,
                    r.deviation.pos_p95_rel_diag);
      line += buf;
    }
  }
  if (r.status != RunStatus::Ok) line += "  FAILED: " + printable(r.message);
  else if (!r.message.empty()) line += "  (" + printable(r.message) + ")";
  return line;
}

void print_row(const RunRow& r) { std::printf("%s%s\n", row_head(r).c_str(), row_figures(r).c_str()); }

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
  if (!m.vulkan_device.empty())
    std::printf(", %s %.2f GB/s (buffer fill; a store-only shader %.2f)", m.vulkan_device.c_str(),
                m.gpu_write_bandwidth_gbs, m.gpu_shader_write_bandwidth_gbs);
  if (!m.opengl_renderer.empty()) std::printf(", OpenGL: %s", m.opengl_renderer.c_str());
  std::printf("\n");
}

RunSelection run_selection(const RunOptions& opts) {
  RunSelection r;
  Selection& sel = r.selection;
  sel.schemes = opts.schemes, sel.meshes = opts.meshes, sel.backends = opts.backends, sel.levels = opts.levels;
  sel.all_meshes = opts.all_meshes || opts.all_corpus;
  sel.all_corpus = opts.all_corpus;
  sel.quick = opts.quick;
  if (!opts.shard.empty()) std::tie(sel.shard_index, sel.shard_count) = parse_shard(opts.shard);
  r.reps = opts.reps, r.rays = opts.rays, r.seed = opts.seed, r.validate = !opts.no_validate;
  return r;
}

// The summary cells timed in paired rounds beside each other (paired.h), with their progress.
std::vector<PairedCell> paired_figures(RunSet& set, const ResultsFile& results, const RunOptions& opts) {
  const std::vector<PairedPlanCell> cells = choose_paired_cells(results.runs);
  if (cells.empty()) {
    std::printf("paired rounds: none (no ok row has its peer's row in this run)\n");
    return {};
  }
  const size_t items = paired_items(cells, opts.rounds);
  const size_t gpu = size_t(std::count_if(cells.begin(), cells.end(), [](const PairedPlanCell& c) { return is_backend_cell(c); }));
  std::printf("paired rounds: %zu summary cells (each scheme+backend at the level nearest 1 M triangles against its peer) "
              "and %zu GPU rows against their scheme's cpu-mt row, %d rounds on each of %zu meshes\n",
              cells.size() - gpu, gpu, opts.rounds, items / size_t(opts.rounds));
  std::fflush(stdout);
  Progress progress(std::cout, stdout_is_terminal(), items, Progress::steady_seconds, terminal_columns());
  auto note = [&](const std::string& line) { progress.note("note: " + line); };
  return measure_paired(cells, {opts.rounds, kPairedMinTime}, set.context(), &progress, note);
}

// A row worth keeping on screen while a terminal shows only the status line.
bool notable(const RunRow& r) { return r.status == RunStatus::Failed || has_crack(r); }

// `selection_given`: with --resume, whether the command line named a selection of its own (it
// must then be the journalled one) or leaves it to the journal.
// The report's pictures: the paper schemes among those the run selected (all of them when it
// selected none) on the pictures' own meshes, which show each surface whatever meshes were timed.
// None in a shard: the merged report takes them from one place, not from N copies.
std::optional<pictures::PictureRequest> picture_request(const RunOptions& opts, const Selection& selection) {
  if (opts.no_pictures || opts.no_report || selection.shard_count > 1) return std::nullopt;
  pictures::PictureRequest request;
  if (selection.schemes.empty()) return request;
  const std::vector<std::string> drawable = pictures::default_schemes();
  for (const std::string& spec : selection.schemes)
    if (std::find(drawable.begin(), drawable.end(), spec.substr(0, spec.find(':'))) != drawable.end())
      request.schemes.push_back(spec);
  if (request.schemes.empty()) return std::nullopt;
  return request;
}

// Why the run's report has no paper tables, or "" when the run measures them: they come with the
// whole set (quick or default), not with a selection of schemes, meshes or levels, nor with a shard.
std::string papers_left_out(const RunOptions& opts, const Selection& selection) {
  if (opts.no_papers) return "no paper table: the run was asked not to measure them (--no-papers)";
  if (selection.shard_count > 1) return "no paper table in a shard: `subdivbench paper ID` measures each";
  if (!selection.schemes.empty() || !selection.meshes.empty() || !selection.levels.empty() || !selection.backends.empty())
    return "no paper table: this run measured a selection; `subdivbench run` without one (or `subdivbench paper ID`) "
           "measures them";
  return "";
}

// Every registered paper table (harness/core/paper_table.h), the quick version with the quick set:
// each writes DIR/paper/ID.md. A table that fails is named, with why, in the report; the run goes on.
std::pair<std::vector<std::string>, std::string> measure_paper_tables(const std::string& dir, bool quick) {
  std::vector<std::string> written;
  std::string failed;
  for (const PaperTable& t : paper_tables()) {
    PaperTableOptions options;
    options.out_dir = (std::filesystem::path(dir) / "paper").string();
    options.quick = quick;
    std::printf("paper table %s%s\n", t.id.c_str(), quick ? " (quick)" : "");
    std::fflush(stdout);
    std::ostringstream printed;  // the table is in ID.md; run's own output stays its rows
    try {
      t.run(options, printed);
      const std::string md = (std::filesystem::path(options.out_dir) / (t.id + ".md")).string();
      if (std::filesystem::is_regular_file(md)) written.push_back(md);
      else failed += (failed.empty() ? "" : "; ") + t.id + ": wrote no table";
    } catch (const std::exception& e) {
      failed += (failed.empty() ? "" : "; ") + t.id + ": " + printable(e.what());
    }
  }
  return {written, failed.empty() ? "" : "not in this report: " + failed};
}

RunSet::ReportWriter report_writer(const RunOptions& opts, const Selection& selection) {
  if (opts.no_report) return {};
  const std::optional<pictures::PictureRequest> request = picture_request(opts, selection);
  const std::string no_papers = papers_left_out(opts, selection);
  const bool quick = selection.quick;
  return [request, no_papers, quick](const std::string& results_json, const std::string& dir) {
    if (request) {
      const pictures::PictureManifest m = pictures::write_pictures(*request, dir);
      gpu::release_shared_context();
      std::printf("pictures: %s\n", m.available ? (std::to_string(m.pictures.size()) + " on " + m.device).c_str()
                                                : ("none: " + m.reason).c_str());
    }
    ReportOptions options;
    options.papers_note = no_papers;
    if (no_papers.empty()) std::tie(options.papers, options.papers_note) = measure_paper_tables(dir, quick);
    gpu::release_shared_context();
    write_report({results_json}, dir, options);
  };
}

// `run --plan`: the rows the selection would measure, counted per backend, and nothing measured
// or written (the README's counts come from here).
int print_plan(const RunOptions& opts) {
  const RunSelection selection = run_selection(opts);
  MeasureContext ctx(describe_machine());
  const Plan plan = make_plan(selection.selection, ctx);
  for (const auto& n : plan.notes) std::printf("note: %s\n", n.c_str());
  std::map<std::string, size_t> per_backend;
  std::set<std::string> meshes;
  for (const RunSpec& r : plan.runs) ++per_backend[std::string(to_string(r.backend))], meshes.insert(r.mesh);
  const Selection& sel = selection.selection;
  const bool whole = sel.schemes.empty() && sel.meshes.empty() && sel.levels.empty() && !sel.all_meshes;
  std::printf("%s: %zu rows on %zu meshes (", sel.quick ? "quick set" : whole ? "default set" : "selection",
              plan.runs.size(), meshes.size());
  bool first = true;
  for (const auto& [backend, n] : per_backend) std::printf("%s%s %zu", first ? "" : ", ", backend.c_str(), n), first = false;
  std::printf(")\n");
  return 0;
}

int run(const RunOptions& opts, bool selection_given) {
  if (opts.plan_only) return print_plan(opts);
  const bool isolate = !opts.in_process;
  RunSet set = opts.resume.empty()
                   ? RunSet::start(opts.out, run_selection(opts), isolate, opts.force)
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
  std::fflush(stdout);
  {
    Progress progress(std::cout, stdout_is_terminal(), set.remaining(), Progress::steady_seconds, terminal_columns());
    set.measure_remaining([&](const RunRow& row) { progress.done(row_head(row), row_figures(row), notable(row)); },
                          [&](const RunSpec& spec) { progress.begin(spec.name()); });
  }
  ResultsFile results = set.results();
  RunOptions paired_opts = opts;  // a resumed quick run keeps the quick set's rounds
  if (!opts.rounds_given && set.selection().selection.quick) paired_opts.rounds = kQuickRounds;
  // A shard lacks the rest of the selection: which level is nearest 1 M, and the peer's row, may
  // lie in another shard, so its cells would be partial and the merged shards' contradictory.
  if (set.selection().selection.shard_count > 1)
    std::printf("paired rounds: none in a shard (its summary cells may lie in other shards); the merged report's "
                "ratios are single-pass\n");
  else if (!opts.no_paired)
    results.paired = paired_figures(set, results, paired_opts);
  set.publish(results, report_writer(opts, set.selection().selection));
  const RunSummary summary = summarise(results.runs);
  std::printf("\n");
  for (const std::string& line : paired_lines(results.paired, &results.machine)) std::printf("%s\n", line.c_str());
  for (const std::string& line :
       summary_lines(summary, (std::filesystem::path(out) / "results.json").string(), opts.no_report ? "" : out))
    std::printf("%s\n", line.c_str());
  return summary.failed > 0 ? 1 : 0;
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
  v->add_option("--rays", opts->rays, "random lines (as many again aimed at patch borders), at most 10000000")
      ->check(CLI::Range(0L, kMaxRays));
  v->add_option("--seed", opts->seed, "seed of the ray generator");
  v->add_flag("--json", opts->json, "print the row as JSON (results.json row format)");
  v->add_option("--deviation-out", opts->deviation_ply, "write the output with per-vertex deviation as a PLY file");
  verbs["validate"] = [opts] { return validate(*opts); };

  auto* r = app.add_subcommand("run", "Run, validate and time schemes; write results.json and the report");
  add_selection(r, *opts);
  r->add_option("--reps", opts->reps, "timed repetitions per run (1..1000)")->check(CLI::Range(1, kMaxReps));
  r->add_option("--rays", opts->rays, "random lines per run, as many again aimed at patch borders (default 50000, at most 10000000)")
      ->check(CLI::Range(0L, kMaxRays));
  r->add_flag("--no-validate", opts->no_validate, "time only");
  auto* quick = r->add_flag("--quick", opts->quick,
                            "the quick set: every scheme on a quad, a triangle and a real mesh at two levels each "
                            "(about 100 k and 1 M triangles); 3 repetitions, 3 paired rounds and 10000 rays unless "
                            "given, Hausdorff distances only where the deviation is measured by nearest points");
  quick->excludes(r->get_option("--all"))->excludes(r->get_option("--all-corpus"));
  r->add_flag("--full", opts->full,
              "the default set instead of the quick set when nothing is selected: every scheme on the curated meshes at "
              "its default levels and the level nearest 1 M triangles, with its headline runs")
      ->excludes(quick);
  r->add_option("--shard", opts->shard,
                "run shard I of N (0 <= I < N) of the selection: the runs whose position among the sorted run names "
                "is I modulo N (merge the shards' results with `report --in`)");
  // What a resumed run compares with its journal: given at all, the whole selection must match.
  std::vector<const CLI::Option*> selection;
  for (const char* name : {"--scheme", "--mesh", "--backend", "--level", "--all", "--all-corpus", "--reps", "--rays", "--no-validate",
                           "--quick", "--full", "--shard"})
    selection.push_back(r->get_option(name));
  auto* out = r->add_option("--out", opts->out, "output folder (results.json, report, journal.jsonl)");
  r->add_option("--resume", opts->resume,
                "continue the interrupted run journalled in DIR (DIR/journal.jsonl): measure only the rows it lacks")
      ->excludes(out);
  r->add_flag("--force", opts->force, "replace an unfinished run's journal in the output folder (default: refuse, "
                                       "naming it; `--resume DIR` continues it)")
      ->excludes(r->get_option("--resume"));
  r->add_flag("--no-report", opts->no_report, "write results.json only");
  r->add_flag("--plan", opts->plan_only, "print how many rows the selection plans, per backend, and stop")
      ->excludes(r->get_option("--resume"));
  r->add_flag("--no-papers", opts->no_papers,
              "no paper tables in the report (default without a selection: every registered table, the quick "
              "versions unless --full)");
  r->add_flag("--no-pictures", opts->no_pictures,
              "no pictures in the report (default: the paper schemes' surfaces, rendered with Vulkan where a device exists)");
  auto* rounds = r->add_option("--rounds", opts->rounds,
                               "paired rounds of the summary cells: each scheme+backend and its peer timed in the same "
                               "rounds (default 5; 3 with --quick; at most 1000)")
                     ->check(CLI::Range(1, kMaxRounds));
  r->add_flag("--no-paired", opts->no_paired, "skip the paired rounds (the report's ratios are then single-pass)")->excludes(rounds);
  r->add_flag("--in-process", opts->in_process,
              "measure every row in this process, for profilers and debuggers (default: in a worker process, "
              "so that a crash in a library fails its row and the run goes on)");
  const CLI::Option* reps = r->get_option("--reps");
  const CLI::Option* rays = r->get_option("--rays");
  verbs["run"] = [opts, selection, reps, rays, rounds] {
    const bool given = std::any_of(selection.begin(), selection.end(), [](const CLI::Option* o) { return o->count() > 0; });
    // No selection at all: the quick set (README, "Quick start"); --full asks for the default set.
    const bool chose = !opts->schemes.empty() || !opts->meshes.empty() || !opts->levels.empty() || opts->all_meshes ||
                       opts->all_corpus;
    if (!opts->full && !chose && opts->resume.empty()) opts->quick = true;
    if (opts->quick && reps->count() == 0) opts->reps = kQuickReps;
    opts->rounds_given = rounds->count() > 0;
    if (opts->quick && !opts->rounds_given) opts->rounds = kQuickRounds;
    if (opts->quick && rays->count() == 0) opts->rays = kQuickRays;
    return run(*opts, given);
  };

  auto* w = app.add_subcommand("row-worker", "");  // hidden: measures run's rows in a worker process (row_worker.h)
  w->group("");
  w->add_option("--channel-fd", opts->worker_channel)->required();
  w->add_option("--parent", opts->worker_parent)->required();
  verbs["row-worker"] = [opts]() -> int { serve_rows(opts->worker_channel, opts->worker_parent); };
}

}  // namespace sdb::cli
