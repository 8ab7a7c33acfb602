// bench, gate, report, paper and the hidden workload verb: thin wrappers over harness/bench.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "harness/bench/callgrind_workload.h"
#include "harness/bench/machine.h"
#include "harness/bench/measure.h"
#include "harness/bench/paired.h"
#include "harness/run/plan.h"
#include "harness/bench/progress.h"
#include "harness/run/run_summary.h"
#include "app/commands.h"
#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/gate/callgrind.h"
#include "harness/gate/gate.h"
#include "harness/results/process.h"
#include "harness/results/resources.h"
#include "reports/report.h"

namespace fs = std::filesystem;

namespace sdb::app {
namespace {

struct GateOptions {
  std::vector<std::string> schemes, meshes, backends, inputs, runs;
  std::string workload_config;  // bench --workload FILE: the "workload" of a gate configuration
  std::string machine_from;     // bench --machine-from FILE: its machine block, probes included
  std::vector<int> levels;
  std::string out, baseline, current, config = resource_path("ci/gate.json");
  std::string machine_baselines;  // gate: a folder of per-machine baselines (ci/baselines)
  bool record_machine = false;    // gate: copy --current into that folder, named for its machine
  bool callgrind = false, record = false;
  std::string scheme, mesh, backend = "cpu";
  int level = 0, iterations = 3, rounds = 0;
  std::string paper_id, texture;
  bool quick = false;
  std::vector<std::string> bench_flags;  // passed to Google Benchmark
};

// A run named on its own (--run) that its scheme declines (a level out of range, a
// backend it lacks) is bad usage, as in `validate`: Google Benchmark alone would say that no
// benchmark matched, and exit 0.
void require_runnable(const std::vector<RunSpec>& runs) {
  for (const RunSpec& spec : runs) {
    const ResolvedScheme r = resolve_scheme(spec.scheme);
    if (auto why = declined(*r.scheme, {spec.backend, spec.level, 0, r.parameters})) throw InputError(spec.name(), *why);
  }
}

// A run named on its own that was not measured (a limit met in its preparation, after the
// others ran): the error to give once the measured rows are written.
std::optional<InputError> unmeasured(const std::vector<RunSpec>& runs, const std::vector<RunRow>& rows) {
  for (const RunSpec& spec : runs)
    if (std::none_of(rows.begin(), rows.end(), [&](const RunRow& r) { return r.name() == spec.name(); }))
      return InputError(spec.name(), "not measured (a size or device limit; `validate` says which)");
  return std::nullopt;
}

int bench(const GateOptions& opts) {
  if (!opts.out.empty()) prepare_output_folder(opts.out);
  // bench --machine-from FILE: gpu-check's device stage measured the probes once for several bench
  // processes (machine.h); otherwise the probes ctest's earlier processes kept, or this one's.
  MeasureContext ctx(opts.machine_from.empty() ? describe_machine_or_reuse() : machine_from(opts.machine_from));
  Selection sel;
  sel.schemes = opts.schemes, sel.meshes = opts.meshes, sel.backends = opts.backends, sel.levels = opts.levels;
  Plan plan;
  if (!opts.workload_config.empty()) plan.runs = read_gate_config(opts.workload_config).workload;
  else if (opts.runs.empty()) plan = make_plan(sel, ctx);
  for (const auto& name : opts.runs) plan.runs.push_back(parse_run_name(name));
  plan.runs = distinct_runs(plan.runs, &plan.notes);
  // The workload's rows may lack a device here (its Vulkan rows): the gate judges what is missing.
  const bool named = opts.workload_config.empty() && !opts.runs.empty();
  if (named) require_runnable(plan.runs);
  if (opts.machine_from.empty()) ctx.probe_bandwidth();  // after the selection is known to be good: a bad one is said at once
  for (const auto& n : plan.notes) std::fprintf(stderr, "note: %s\n", n.c_str());
  if (!parse_benchmark_flags("subdivbench bench", opts.bench_flags)) return 2;
  MeasureOptions m;
  m.validate = false;
  ResultsFile results;
  results.machine = ctx.machine();
  results.rounds = opts.rounds;
  // Rounds run quietly until the end (one table); their progress is shown instead. Without rounds
  // Google Benchmark's console prints each benchmark as it finishes.
  BenchRounds how{opts.rounds};
  how.every_spec_named = named;
  std::optional<Progress> progress;
  if (opts.rounds > 0)
    how.progress = &progress.emplace(std::cout, stdout_is_terminal(), size_t(opts.rounds), Progress::steady_seconds, terminal_columns());
  results.runs = bench_runs(plan.runs, m, ctx, benchmark_console(), how);
  if (progress) progress->close();
  const bool filtered = std::any_of(opts.bench_flags.begin(), opts.bench_flags.end(),
                                    [](const std::string& f) { return f.rfind("--benchmark_filter", 0) == 0; });
  // A failure never destroys what was measured: the rows that ran are printed and written first.
  const std::optional<InputError> missing = named && !filtered ? unmeasured(plan.runs, results.runs) : std::nullopt;
  if (opts.rounds > 0) {
    for (const RunRow& r : results.runs)
      std::printf("%-44s median %9.4f ms  min %9.4f ms  over %d rounds\n", r.name().c_str(), r.time_ms.median,
                  r.time_ms.min, r.time_ms.reps);
    // Every row ran once per round: a row and its peer, or a GPU row and its scheme's cpu-mt row,
    // pair by round as they are (results.json's paired, the report's ratios).
    results.paired = pair_measured_rows(results.runs);
    for (const std::string& line : paired_lines(results.paired, &results.machine)) std::printf("%s\n", line.c_str());
  }
  if (!opts.out.empty()) {
    write_results(results, (fs::path(opts.out) / "results.json").string());
    std::printf("wrote %s\n", (fs::path(opts.out) / "results.json").string().c_str());
  }
  if (missing) throw *missing;
  return 0;
}

int callgrind_gate(const GateOptions& opts) {
  const CallgrindConfig config = read_callgrind_config(opts.config);
  // A bad baseline or an unwritable record path is said before minutes of valgrind, not after.
  if (opts.record) {
    const fs::path parent = fs::path(opts.baseline).parent_path();
    prepare_output_folder(parent.empty() ? "." : parent.string());
  } else {
    const auto baseline = read_callgrind_counts(opts.baseline);
    const bool any = std::any_of(config.workloads.begin(), config.workloads.end(),
                                 [&](const RunSpec& w) { return baseline.count(w.name()) > 0; });
    if (!any)
      throw InputError(opts.baseline, "holds none of the " + std::to_string(config.workloads.size()) + " workloads of " +
                                          opts.config + " (record them with --record)");
  }
  // A machine where valgrind cannot run the binary at all cannot count instructions; that is a
  // limit of the machine, like a missing Vulkan device, not a regression. Comparing is skipped
  // and said; recording still fails, since it was asked for counts that cannot be made.
  if (!opts.record) {
    if (auto why = valgrind_unusable(self_executable())) {
      std::printf("gate: instruction counts not compared: %s; the timing gate is the one that ran\n", why->c_str());
      return 0;
    }
  }
  std::map<std::string, long> counts;
  for (const RunSpec& w : config.workloads) counts[w.name()] = callgrind_instructions(w, opts.iterations, self_executable());
  if (opts.record) {
    write_callgrind_counts(counts, opts.baseline);
    std::printf("recorded %zu instruction counts in %s\n", counts.size(), opts.baseline.c_str());
    return 0;
  }
  const auto entries = callgrind_compare(config, counts, read_callgrind_counts(opts.baseline));
  bool failed = false;
  std::printf("%-44s %14s %14s %8s\n", "workload (instructions in execute)", "baseline", "current", "change");
  for (const CallgrindEntry& e : entries) {
    failed |= e.regression;
    std::printf("%-44s %14.0f %14.0f %+7.2f%%%s\n", e.name.c_str(), e.baseline, e.current, 100 * e.change,
                e.regression ? "  REGRESSION" : "");
  }
  return failed ? 1 : 0;
}

// The .json files of a folder of per-machine baselines, by name; none where the folder is absent.
std::vector<std::string> machine_baseline_files(const std::string& dir) {
  std::vector<std::string> files;
  if (dir.empty() || !fs::is_directory(dir)) return files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == ".json") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

// gate --record-machine: the current results become this machine's baseline in the folder.
int record_machine_baseline(const GateOptions& opts) {
  if (opts.machine_baselines.empty() || opts.current.empty())
    throw InputError("gate", "--record-machine needs --machine-baselines DIR and --current FILE");
  const ResultsFile current = read_results(opts.current);
  if (current.machine.cpu_model.empty()) throw InputError(opts.current, "names no processor to record a baseline for");
  fs::create_directories(opts.machine_baselines);
  const fs::path path = fs::path(opts.machine_baselines) / machine_baseline_name(current.machine);
  fs::copy_file(opts.current, path, fs::copy_options::overwrite_existing);
  std::printf("gate: baseline for %s (%d cores) recorded in %s\n", current.machine.cpu_model.c_str(),
              current.machine.cores, path.string().c_str());
  return 0;
}

int gate(const GateOptions& opts) {
  if (opts.callgrind) return callgrind_gate(opts);
  if (opts.record_machine) return record_machine_baseline(opts);
  if (opts.current.empty()) throw InputError("gate", "--current FILE is required (or --callgrind)");
  const GateConfig config = read_gate_config(opts.config);
  const ResultsFile current = read_results(opts.current);
  std::string baseline = opts.baseline;
  if (auto own = baseline_for_machine(current.machine, machine_baseline_files(opts.machine_baselines))) {
    baseline = *own;
    std::printf("gate: this machine's baseline: %s\n", baseline.c_str());
  }
  const GateReport report = run_gate(read_results(baseline), current, config);
  std::printf("%-44s %-22s %9s %9s %9s  %s\n", "benchmark", "normalised by", "change", "p-value", "threshold", "verdict");
  for (const GateEntry& e : report.entries)
    std::printf("%-44s %-22s %+8.1f%% %9.4f %8.0f%%  %s\n", e.name.c_str(), e.normaliser.c_str(), 100 * e.change,
                e.p_value, 100 * e.threshold, e.regression ? "REGRESSION" : e.improvement ? "improvement" : "same");
  for (const std::string& name : report.new_rows) std::printf("%-44s new: no baseline row, not judged\n", name.c_str());
  for (const GateGap& g : report.gaps) std::printf("%-44s NO OK ROW: %s\n", g.name.c_str(), g.why.c_str());
  for (const auto& p : report.problems) std::printf("cannot judge %s\n", p.c_str());
  if (report.entries.empty() && report.problems.empty() && report.gaps.empty())
    throw InputError(opts.current, "no benchmark in common with the baseline");
  // Before the problems' exit 2: a benchmark that stopped running is a failed check, said as one.
  if (!report.gaps.empty()) {
    std::printf("gate: FAILED: %zu of the baseline's benchmarks have no ok row in %s (first: %s, %s)\n", report.gaps.size(),
                opts.current.c_str(), report.gaps.front().name.c_str(), report.gaps.front().why.c_str());
    return 1;
  }
  if (!report.problems.empty())
    throw InputError(opts.current, std::to_string(report.problems.size()) + " benchmarks cannot be judged (first: " +
                                       report.problems.front() + ")");
  if (!report.other_machine.empty())
    std::printf("gate: timing verdicts not enforced: %s; ratios between kernels differ between processors. Record "
                "a baseline on this machine (scripts/gate --record-here) to gate here\n",
                report.other_machine.c_str());
  return report.failed() ? 1 : 0;
}

int paper(const GateOptions& opts) {
  if (opts.paper_id.empty() || opts.paper_id == "list") {
    std::printf("%-24s %s\n", "id", "table");
    for (const auto& t : paper_tables()) std::printf("%-24s %s\n", t.id.c_str(), t.title.c_str());
    return 0;
  }
  for (const auto& t : paper_tables())
    if (t.id == opts.paper_id) {
      PaperTableOptions options;
      if (!opts.out.empty()) options.out_dir = opts.out;
      options.quick = opts.quick;
      options.texture = opts.texture;
      // On standard error: the table on standard output stays what the paper verb writes.
      Progress progress(std::cerr, stderr_is_terminal(), 0, Progress::steady_seconds, terminal_columns());
      MeasureObserver observer([&](const RunSpec& spec) { progress.begin(spec.name()); },
                               [&](const RunRow& row) {
                                 progress.done(row.name(), "  " + std::string(to_string(row.status)), row.status == RunStatus::Failed);
                               });
      return t.run(options, std::cout);
    }
  throw InputError(opts.paper_id, "no such paper table (see `subdivbench paper list`)");
}

int report(const std::vector<std::string>& inputs, const std::string& out, const ReportOptions& options) {
  const std::string dir = out.empty() ? "." : out;
  write_report(inputs, dir, options);
  std::printf("wrote %s and %s\n", (fs::path(dir) / "report.md").string().c_str(), (fs::path(dir) / "report.html").string().c_str());
  return 0;
}

int workload(const GateOptions& opts) {
  const auto backend = parse_backend(opts.backend);
  if (!backend) throw InputError("--backend", "unknown backend '" + opts.backend + "'");
  run_callgrind_workload({opts.scheme, opts.mesh, *backend, opts.level}, opts.iterations);
  return 0;
}

}  // namespace

void add_gate_verbs(CLI::App& app, Verbs& verbs) {
  auto opts = std::make_shared<GateOptions>();
  auto* b = app.add_subcommand("bench", "Google Benchmark over a selection; flags --benchmark_* pass through");
  b->add_option("--scheme", opts->schemes, "scheme, with parameters as name:key=value (repeatable)");
  b->add_option("--mesh", opts->meshes, "mesh (repeatable)");
  b->add_option("--backend", opts->backends, "backend (repeatable)");
  b->add_option("--level", opts->levels, "level (repeatable)");
  b->add_option("--run", opts->runs, "one benchmark, scheme/backend/mesh/level (repeatable; instead of the selection)");
  b->add_option("--workload", opts->workload_config, "the workload of a gate configuration (ci/gate.json) instead of the selection");
  b->add_option("--out", opts->out, "folder for results.json");
  b->add_option("--machine-from", opts->machine_from,
                "take the machine block and its bandwidth probes from this results file (of this machine and build) "
                "instead of measuring the probes");
  b->add_option("--rounds", opts->rounds, "run in this many rounds, every benchmark once per round in random order "
                                          "(the gate pairs samples by round; at most 1000); default: Google Benchmark's flags")
      ->check(CLI::Range(0, kMaxRounds));
  b->allow_extras();
  b->callback([b, opts] { opts->bench_flags = b->remaining(); });
  verbs["bench"] = [opts] { return bench(*opts); };

  auto* gt = app.add_subcommand("gate", "Fail on a significant performance regression against a baseline");
  gt->add_option("--baseline", opts->baseline, "baseline results.json (or callgrind counts with --callgrind)")->required();
  gt->add_option("--current", opts->current, "current results.json");
  gt->add_option("--config", opts->config, "thresholds (ci/gate.json)");
  gt->add_flag("--callgrind", opts->callgrind, "compare instruction counts of the fixed workloads instead of time");
  gt->add_flag("--record", opts->record, "with --callgrind: write the counts to --baseline");
  gt->add_option("--machine-baselines", opts->machine_baselines,
                 "folder of per-machine baselines: one recorded on this processor and core count replaces --baseline");
  gt->add_flag("--record-machine", opts->record_machine,
               "copy --current into --machine-baselines as this machine's baseline");
  verbs["gate"] = [opts] { return gate(*opts); };

  struct ReportRequest {
    std::vector<std::string> inputs;
    std::string out;
    ReportOptions options;
  };
  auto report_request = std::make_shared<ReportRequest>();
  auto* r = app.add_subcommand("report", "Write report.md and report.html from results files");
  r->add_option("--in", report_request->inputs,
                "results.json (repeatable): the shards of one sweep, merged; with --history, one per commit")
      ->required();
  r->add_option("--out", report_request->out, "output folder");
  r->add_option("--paper", report_request->options.papers, "a paper table's Markdown, from `subdivbench paper ID` (repeatable)");
  r->add_flag("--history", report_request->options.history,
              "the --in files are one per commit, oldest first: draw each gated benchmark's normalised time per commit");
  r->add_flag("--allow-mixed", report_request->options.allow_mixed, "merge files from different commits or machines");
  verbs["report"] = [report_request] { return report(report_request->inputs, report_request->out, report_request->options); };

  auto* p = app.add_subcommand("paper", "A paper's table, the paper's figures and ours side by side");
  p->add_option("id", opts->paper_id, "table id, or `list`");
  p->add_option("--out", opts->out, "folder for the table and its pictures (default results/paper)");
  p->add_flag("--quick", opts->quick, "fewer and smaller cells (what the tests run)");
  p->add_option("--texture", opts->texture, "an image the table reads (shiue2003-fig22: its displacement map)");
  verbs["paper"] = [opts] { return paper(*opts); };

  auto* w = app.add_subcommand("workload", "");  // hidden: what the callgrind gate counts
  w->group("");
  w->add_option("--scheme", opts->scheme)->required();
  w->add_option("--mesh", opts->mesh)->required();
  w->add_option("--level", opts->level)->required();
  w->add_option("--iterations", opts->iterations);
  // Also by hand, to count a Vulkan kernel's instructions on lavapipe (harness/bench/README.md).
  w->add_option("--backend", opts->backend);
  verbs["workload"] = [opts] { return workload(*opts); };
}

}  // namespace sdb::app
