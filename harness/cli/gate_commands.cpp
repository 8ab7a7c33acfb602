#include "gate_commands.h"

#include <benchmark/benchmark.h>
#include <unistd.h>
#include <valgrind/callgrind.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>

#include "errors.h"
#include "gate.h"
#include "machine.h"
#include "manifest.h"
#include "measure.h"
#include "paper_tables.h"
#include "plan.h"
#include "registry.h"
#include "report.h"

namespace fs = std::filesystem;

namespace sdb::cli {
namespace {

struct GateOptions {
  std::vector<std::string> schemes, meshes, backends, inputs, runs;
  std::vector<int> levels;
  std::string out, baseline, current, config = SDB_SOURCE_DIR "/ci/gate.json";
  bool callgrind = false, record = false;
  std::string scheme, mesh;
  int level = 0, iterations = 3, rounds = 0;
  std::string paper_id;
  bool quick = false;
};
GateOptions g;
std::vector<std::string> bench_flags;  // passed to Google Benchmark

RunSpec parse_run_name(const std::string& name) {
  static const std::regex parts(R"(([^/]+)/([^/]+)/(.+)/(\d+))");
  std::smatch m;
  if (!std::regex_match(name, m, parts)) throw InputError(name, "expected scheme/backend/mesh/level");
  const auto backend = parse_backend(m[2].str());
  if (!backend) throw InputError(name, "no such backend '" + m[2].str() + "'");
  return {m[1].str(), m[3].str(), *backend, std::stoi(m[4].str())};
}

int bench() {
  MeasureContext ctx(describe_machine_with_probes());
  Selection sel;
  sel.schemes = g.schemes, sel.meshes = g.meshes, sel.backends = g.backends, sel.levels = g.levels;
  Plan plan;
  if (g.runs.empty()) plan = make_plan(sel, ctx);
  for (const auto& name : g.runs) plan.runs.push_back(parse_run_name(name));
  for (const auto& n : plan.notes) std::fprintf(stderr, "note: %s\n", n.c_str());
  std::vector<std::string> args = {"subdivbench bench"};
  args.insert(args.end(), bench_flags.begin(), bench_flags.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  int argc = static_cast<int>(argv.size());
  benchmark::Initialize(&argc, argv.data());
  if (benchmark::ReportUnrecognizedArguments(argc, argv.data())) return 2;
  benchmark::ConsoleReporter console;
  MeasureOptions o;
  o.validate = false;
  ResultsFile results;
  results.machine = ctx.machine();
  results.rounds = g.rounds;
  results.runs = bench_runs(plan.runs, o, ctx, &console, g.rounds);
  if (g.rounds > 0)
    for (const RunRow& r : results.runs)
      std::printf("%-44s median %9.4f ms  min %9.4f ms  over %d rounds\n", (r.scheme + "/" + r.backend + "/" + r.mesh + "/" +
                  std::to_string(r.level)).c_str(), r.time_ms.median, r.time_ms.min, r.time_ms.reps);
  if (!g.out.empty()) {
    fs::create_directories(g.out);
    write_results(results, (fs::path(g.out) / "results.json").string());
    std::printf("wrote %s\n", (fs::path(g.out) / "results.json").string().c_str());
  }
  return 0;
}

// --- deterministic gate: instruction counts under callgrind ---------------------------------

int workload() {
  MeasureContext ctx(MachineInfo{});
  const Scheme* scheme = find_scheme(g.scheme);
  if (!scheme) throw InputError(g.scheme, "no such scheme");
  const auto mesh = ctx.accepted(g.mesh, *scheme);
  auto eval = scheme->prepare(*mesh, {Backend::Cpu, g.level, 0});
  CALLGRIND_START_INSTRUMENTATION;  // count execute() only, not loading or prepare()
  const int runs = planted_slowdown(g.scheme) ? 2 : 1;
  for (int i = 0; i < g.iterations * runs; ++i) execute_on(*eval, Backend::Cpu);
  CALLGRIND_STOP_INSTRUMENTATION;
  return 0;
}

long callgrind_instructions(const std::string& name) {
  const std::regex parts(R"(([^/]+)/cpu/(.+)/(\d+))");
  std::smatch m;
  if (!std::regex_match(name, m, parts)) throw InputError(name, "callgrind workloads are scheme/cpu/mesh/level");
  const fs::path out = fs::temp_directory_path() / ("sdb_callgrind_" + std::to_string(getpid()) + ".out");
  const std::string self = fs::read_symlink("/proc/self/exe").string();
  const std::string cmd = "valgrind --tool=callgrind --instr-atstart=no --callgrind-out-file=" + out.string() + " " +
                          self + " workload --scheme " + m[1].str() + " --mesh '" + m[2].str() + "' --level " +
                          m[3].str() + " --iterations " + std::to_string(g.iterations) + " >/dev/null 2>&1";
  if (std::system(cmd.c_str()) != 0) throw InputError(name, "valgrind --tool=callgrind failed (is valgrind installed?)");
  std::ifstream in(out);
  long total = -1;
  for (std::string line; std::getline(in, line);)
    if (line.rfind("summary:", 0) == 0 || line.rfind("totals:", 0) == 0) total = std::stol(line.substr(line.find(':') + 1));
  fs::remove(out);
  if (total < 0) throw InputError(name, "no instruction total in callgrind's output");
  return total;
}

int callgrind_gate() {
  std::ifstream cfg(g.config);
  nlohmann::json config;
  cfg >> config;
  const auto names = config.at("callgrind").at("workloads").get<std::vector<std::string>>();
  const double threshold = config.at("callgrind").value("threshold", 0.02);
  nlohmann::json counts;
  for (const auto& n : names) counts[n] = callgrind_instructions(n);
  if (g.record) {
    std::ofstream(g.baseline) << counts.dump(2) << "\n";
    std::printf("recorded %zu instruction counts in %s\n", names.size(), g.baseline.c_str());
    return 0;
  }
  std::ifstream bin(g.baseline);
  if (!bin) throw InputError(g.baseline, "cannot open callgrind baseline");
  nlohmann::json base;
  bin >> base;
  bool failed = false;
  std::printf("%-44s %14s %14s %8s\n", "workload (instructions in execute)", "baseline", "current", "change");
  for (const auto& n : names) {
    if (!base.contains(n)) continue;
    const double b = base[n].get<double>(), c = counts[n].get<double>(), change = c / b - 1;
    const bool bad = change > threshold;
    failed |= bad;
    std::printf("%-44s %14.0f %14.0f %+7.2f%%%s\n", n.c_str(), b, c, 100 * change, bad ? "  REGRESSION" : "");
  }
  return failed ? 1 : 0;
}

// --- timed gate ------------------------------------------------------------------------------

int gate() {
  if (g.callgrind) return callgrind_gate();
  if (g.current.empty()) throw InputError("gate", "--current FILE is required (or --callgrind)");
  const GateConfig config = read_gate_config(g.config);
  const GateReport report = run_gate(read_results(g.baseline), read_results(g.current), config);
  std::printf("%-44s %-15s %9s %9s %9s  %s\n", "benchmark", "normalised by", "change", "p-value", "threshold", "verdict");
  for (const GateEntry& e : report.entries)
    std::printf("%-44s %-15s %+8.1f%% %9.4f %8.0f%%  %s\n", e.name.c_str(), e.normaliser.c_str(), 100 * e.change, e.p_value,
                100 * e.threshold, e.regression ? "REGRESSION" : e.improvement ? "improvement" : "same");
  for (const auto& p : report.problems) std::printf("cannot judge %s\n", p.c_str());
  if (report.entries.empty() && report.problems.empty()) throw InputError(g.current, "no benchmark in common with the baseline");
  if (!report.problems.empty()) return 2;
  return report.failed() ? 1 : 0;
}

int paper() {
  if (g.paper_id.empty() || g.paper_id == "list") {
    std::printf("%-24s %s\n", "id", "table");
    for (const auto& t : paper_tables()) std::printf("%-24s %s\n", t.id.c_str(), t.title.c_str());
    return 0;
  }
  for (const auto& t : paper_tables())
    if (t.id == g.paper_id) {
      PaperTableOptions options;
      if (!g.out.empty()) options.out_dir = g.out;
      options.quick = g.quick;
      return t.run(options, std::cout);
    }
  throw InputError(g.paper_id, "no such paper table (see `subdivbench paper list`)");
}

int report() {
  if (g.inputs.empty()) throw InputError("report", "--in FILE is required");
  for (const auto& in : g.inputs) read_results(in);  // refuses unknown schemas with file named
  write_report(g.inputs, g.out.empty() ? "." : g.out);
  std::printf("wrote %s and %s\n", (fs::path(g.out) / "report.md").string().c_str(),
              (fs::path(g.out) / "report.html").string().c_str());
  return 0;
}

}  // namespace

void register_gate_commands(CLI::App& app, std::map<std::string, std::function<int()>>& verbs) {
  auto* b = app.add_subcommand("bench", "Google Benchmark over a selection; flags --benchmark_* pass through");
  b->add_option("--scheme", g.schemes, "scheme (repeatable)");
  b->add_option("--mesh", g.meshes, "mesh (repeatable)");
  b->add_option("--backend", g.backends, "backend (repeatable)");
  b->add_option("--level", g.levels, "level (repeatable)");
  b->add_option("--run", g.runs, "one benchmark, scheme/backend/mesh/level (repeatable; instead of the selection)");
  b->add_option("--out", g.out, "folder for results.json");
  b->add_option("--rounds", g.rounds, "run in this many rounds, every benchmark once per round in random order "
                                      "(the gate pairs samples by round); default: Google Benchmark's flags");
  b->allow_extras();
  b->callback([b] { bench_flags = b->remaining(); });
  verbs["bench"] = bench;

  auto* gt = app.add_subcommand("gate", "Fail on a significant performance regression against a baseline");
  gt->add_option("--baseline", g.baseline, "baseline results.json (or callgrind counts with --callgrind)")->required();
  gt->add_option("--current", g.current, "current results.json");
  gt->add_option("--config", g.config, "thresholds (ci/gate.json)");
  gt->add_flag("--callgrind", g.callgrind, "compare instruction counts of the fixed workloads instead of time");
  gt->add_flag("--record", g.record, "with --callgrind: write the counts to --baseline");
  verbs["gate"] = gate;

  auto* r = app.add_subcommand("report", "Write report.md and report.html from results files");
  r->add_option("--in", g.inputs, "results.json (repeatable)")->required();
  r->add_option("--out", g.out, "output folder");
  verbs["report"] = report;

  auto* p = app.add_subcommand("paper", "A paper's table, the paper's figures and ours side by side");
  p->add_option("id", g.paper_id, "table id, or `list`");
  p->add_option("--out", g.out, "folder for the table and its pictures (default results/paper)");
  p->add_flag("--quick", g.quick, "fewer and smaller cells (what the tests run)");
  verbs["paper"] = paper;

  auto* w = app.add_subcommand("workload", "");  // hidden: what the callgrind gate counts
  w->group("");
  w->add_option("--scheme", g.scheme)->required();
  w->add_option("--mesh", g.mesh)->required();
  w->add_option("--level", g.level)->required();
  w->add_option("--iterations", g.iterations);
  verbs["workload"] = workload;
}

}  // namespace sdb::cli
