// validate and run: one checked run, or a selection measured and written with its report.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <tuple>

#include "harness/bench/machine.h"
#include "harness/bench/measure.h"
#include "app/commands.h"
#include "harness/core/errors.h"
#include "harness/gpu/context.h"
#include "harness/pictures/pictures.h"
#include "harness/results/results.h"
#include "harness/run/row_lines.h"
#include "harness/run/row_worker.h"
#include "harness/run/run_pipeline.h"
#include "reports/report.h"

namespace sdb::app {
namespace {

constexpr int kQuickReps = 3;
constexpr long kQuickRays = 10000;

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
  int rounds = kPairedRounds;  // paired rounds of the summary cells
  bool rounds_given = false;    // none given: the pipeline's default for the run's set
  int worker_channel = -1;
  long worker_parent = 0;
};

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

// The report's pictures: the paper schemes among those the run selected (all of them when it
// selected none) on the pictures' own meshes, which show each surface whatever meshes were timed.
// None in a shard: the merged report takes them from one place, not from N copies.
std::optional<pictures::PictureRequest> picture_request(const RunOptions& opts, const Selection& selection) {
  if (opts.no_pictures || selection.shard_count > 1) return std::nullopt;
  pictures::PictureRequest request;
  if (selection.schemes.empty()) return request;
  const std::vector<std::string> drawable = pictures::default_schemes();
  for (const std::string& spec : selection.schemes)
    if (std::find(drawable.begin(), drawable.end(), spec.substr(0, spec.find(':'))) != drawable.end())
      request.schemes.push_back(spec);
  if (request.schemes.empty()) return std::nullopt;
  return request;
}

// What run publishes beside results.json, from the modules above the run pipeline: the pictures
// (harness/pictures) and the report (reports/).
RunSinks run_sinks(const RunOptions& opts) {
  RunSinks sinks;
  if (opts.no_report) return sinks;
  sinks.pictures = [opts](const Selection& selection, const std::string& dir) {
    const std::optional<pictures::PictureRequest> request = picture_request(opts, selection);
    if (!request) return;
    const pictures::PictureManifest m = pictures::write_pictures(*request, dir);
    gpu::release_shared_context();
    std::printf("pictures: %s\n", m.available ? (std::to_string(m.pictures.size()) + " on " + m.device).c_str()
                                              : ("none: " + m.reason).c_str());
  };
  sinks.report = [](const std::string& results_json, const std::string& dir, const std::vector<std::string>& papers,
                    const std::string& papers_note) {
    ReportOptions options;
    options.papers = papers;
    options.papers_note = papers_note;
    write_report({results_json}, dir, options);
  };
  return sinks;
}

// `selection_given`: with --resume, whether the command line named a selection of its own (it
// must then be the journalled one) or leaves it to the journal.
int run(const RunOptions& opts, bool selection_given) {
  if (opts.plan_only) return print_plan(run_selection(opts));
  RunPipelineRequest request;
  request.resume = !opts.resume.empty();
  request.out = request.resume ? opts.resume : opts.out;
  if (!request.resume || selection_given) request.selection = run_selection(opts);
  request.isolate = !opts.in_process;
  request.force = opts.force;
  request.paired = !opts.no_paired;
  if (opts.rounds_given) request.rounds = opts.rounds;
  request.papers = !opts.no_papers;
  return run_pipeline(request, run_sinks(opts));
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
    if (opts->quick && rays->count() == 0) opts->rays = kQuickRays;
    return run(*opts, given);
  };

  auto* w = app.add_subcommand("row-worker", "");  // hidden: measures run's rows in a worker process (row_worker.h)
  w->group("");
  w->add_option("--channel-fd", opts->worker_channel)->required();
  w->add_option("--parent", opts->worker_parent)->required();
  verbs["row-worker"] = [opts]() -> int { serve_rows(opts->worker_channel, opts->worker_parent); };
}

}  // namespace sdb::app
