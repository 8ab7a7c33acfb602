#include "harness/run/run_pipeline.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <utility>

#include "harness/bench/machine.h"
#include "harness/bench/paired.h"
#include "harness/bench/progress.h"
#include "harness/core/paper_table.h"
#include "harness/core/printable.h"
#include "harness/gpu/context.h"
#include "harness/run/row_lines.h"
#include "harness/run/run_set.h"
#include "harness/run/run_summary.h"

namespace sdb {
namespace {

// Each benchmark's time in a paired round: long enough to average a few executions of the small
// rows, short enough that a default run's cells cost seconds, not minutes.
constexpr double kPairedMinTime = 0.03;

void print_machine(const MachineInfo& m, size_t runs) {
  std::printf("%zu runs; machine: %s, %d cores, write bandwidth %.1f GB/s (1 thread), %.1f GB/s (all)", runs,
              m.cpu_model.c_str(), m.cores, m.write_bandwidth_gbs, m.write_bandwidth_mt_gbs);
  if (!m.vulkan_device.empty())
    std::printf(", %s %.2f GB/s (buffer fill; a store-only shader %.2f)", m.vulkan_device.c_str(),
                m.gpu_write_bandwidth_gbs, m.gpu_shader_write_bandwidth_gbs);
  if (!m.opengl_renderer.empty()) std::printf(", OpenGL: %s", m.opengl_renderer.c_str());
  std::printf("\n");
}

// The summary cells timed in paired rounds beside each other (paired.h), with their progress.
std::vector<PairedCell> paired_figures(RunSet& set, const ResultsFile& results, int rounds) {
  const std::vector<PairedPlanCell> cells = choose_paired_cells(results.runs);
  if (cells.empty()) {
    std::printf("paired rounds: none (no ok row has its peer's row in this run)\n");
    return {};
  }
  const size_t items = paired_items(cells, rounds);
  const size_t gpu = size_t(std::count_if(cells.begin(), cells.end(), [](const PairedPlanCell& c) { return is_backend_cell(c); }));
  std::printf("paired rounds: %zu summary cells (each scheme+backend at the level nearest 1 M triangles against its peer) "
              "and %zu GPU rows against their scheme's cpu-mt row, %d rounds on each of %zu meshes\n",
              cells.size() - gpu, gpu, rounds, items / size_t(rounds));
  std::fflush(stdout);
  Progress progress(std::cout, stdout_is_terminal(), items, Progress::steady_seconds, terminal_columns());
  auto note = [&](const std::string& line) { progress.note("note: " + line); };
  return measure_paired(cells, {rounds, kPairedMinTime}, set.context(), &progress, note);
}

// A row worth keeping on screen while a terminal shows only the status line.
bool notable(const RunRow& r) { return r.status == RunStatus::Failed || has_crack(r); }

// Why the run's report has no paper tables, or "" when the run measures them: they come with the
// whole set (quick or default), not with a selection of schemes, meshes or levels, nor with a shard.
std::string papers_left_out(bool papers, const Selection& selection) {
  if (!papers) return "no paper table: the run was asked not to measure them (--no-papers)";
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

// What publishing writes beside results.json: the pictures, then the paper tables, then the report
// on both (each device context released before the next stage makes its own).
RunSet::ReportWriter report_writer(const RunSinks& sinks, const Selection& selection, bool papers) {
  if (!sinks.report) return {};
  const std::string no_papers = papers_left_out(papers, selection);
  return [sinks, selection, no_papers](const std::string& results_json, const std::string& dir) {
    if (sinks.pictures) sinks.pictures(selection, dir);
    std::vector<std::string> tables;
    std::string note = no_papers;
    if (no_papers.empty()) std::tie(tables, note) = measure_paper_tables(dir, selection.quick);
    gpu::release_shared_context();
    sinks.report(results_json, dir, tables, note);
  };
}

}  // namespace

int run_pipeline(const RunPipelineRequest& request, const RunSinks& sinks) {
  RunSet set = request.resume ? RunSet::resume(request.out, request.selection, request.isolate)
                              : RunSet::start(request.out, request.selection.value(), request.isolate, request.force);
  for (const auto& n : set.plan().notes) std::printf("note: %s\n", n.c_str());
  if (set.plan().runs.empty()) {
    std::printf("nothing to run for this selection; nothing written\n");
    return 0;
  }
  print_machine(set.machine(), set.plan().runs.size());
  if (request.resume)
    std::printf("resuming %s: %zu of %zu rows journalled%s; measuring %zu\n", request.out.c_str(), set.journalled(),
                set.plan().runs.size(), set.dropped_torn_line() ? " (a torn last line dropped)" : "", set.remaining());
  std::fflush(stdout);
  {
    Progress progress(std::cout, stdout_is_terminal(), set.remaining(), Progress::steady_seconds, terminal_columns());
    set.measure_remaining([&](const RunRow& row) { progress.done(row_head(row), row_figures(row), notable(row)); },
                          [&](const RunSpec& spec) { progress.begin(spec.name()); });
  }
  ResultsFile results = set.results();
  const Selection& selection = set.selection().selection;  // a resumed run's is the journal's
  // A shard lacks the rest of the selection: which level is nearest 1 M, and the peer's row, may
  // lie in another shard, so its cells would be partial and the merged shards' contradictory.
  if (selection.shard_count > 1)
    std::printf("paired rounds: none in a shard (its summary cells may lie in other shards); the merged report's "
                "ratios are single-pass\n");
  else if (request.paired)
    results.paired = paired_figures(set, results, request.rounds.value_or(selection.quick ? kQuickPairedRounds : kPairedRounds));
  set.publish(results, report_writer(sinks, selection, request.papers));
  const RunSummary summary = summarise(results.runs);
  std::printf("\n");
  for (const std::string& line : paired_lines(results.paired, &results.machine)) std::printf("%s\n", line.c_str());
  for (const std::string& line :
       summary_lines(summary, (std::filesystem::path(request.out) / "results.json").string(), sinks.report ? request.out : ""))
    std::printf("%s\n", line.c_str());
  return summary.failed > 0 ? 1 : 0;
}

int print_plan(const RunSelection& selection) {
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

}  // namespace sdb
