#include "reports/report.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/results/output_folder.h"
#include "harness/results/process.h"
#include "harness/results/resources.h"
#include "harness/results/results.h"
#include "harness/results/results_merge.h"
#include "reports/history.h"
#include "reports/overview.h"
#include "reports/report_inputs.h"

namespace fs = std::filesystem;

namespace sdb {
namespace {

// The registry's schemes in its order, as name=role: each scheme's colour in every plot and every
// report follows from it, not from which rows a file happens to hold.
std::string registry_schemes() {
  std::string list;
  for (const auto& s : all_schemes())
    list += (list.empty() ? "" : ",") + s->info().name + "=" + std::string(to_string(s->info().role));
  return list;
}

// "merged from 3 files (shards of 3, all present)"; names the missing shards, so a partial sweep
// is not read as the whole.
std::string merged_from(const std::vector<ResultsFile>& files) {
  std::set<int> have;
  int count = 0;
  for (const auto& f : files)
    if (f.shard) have.insert(f.shard->index), count = std::max(count, f.shard->count);
  if (files.size() < 2 && count < 2) return "";
  std::string words = "merged from " + std::to_string(files.size()) + (files.size() == 1 ? " file" : " files");
  if (count == 0) return words;
  std::string missing;
  for (int i = 0; i < count; ++i)
    if (!have.count(i)) missing += (missing.empty() ? "" : ", ") + std::to_string(i);
  return words + " (shards of " + std::to_string(count) + (missing.empty() ? ", all present)" : "; MISSING: " + missing + ")");
}

// A folder of our own inside out_dir (on the same file system, so the final moves are renames).
fs::path make_work_folder(const fs::path& out_dir) {
  std::string pattern = (out_dir / ".report-XXXXXX").string();
  if (!mkdtemp(pattern.data())) throw InputError(out_dir.string(), "cannot create a folder to write the report in");
  return pattern;
}

// Moves plots/, report.md and report.html from `from` into `out_dir`, the HTML last: its presence
// with a new time means the set is complete. The plots replace ours file by file: a file of the
// user's in out_dir/plots stays.
void move_into_place(const fs::path& from, const fs::path& out_dir) {
  merge_into_folder(from / "plots", out_dir / "plots");
  fs::rename(from / "report.md", out_dir / "report.md");
  fs::rename(from / "report.html", out_dir / "report.html");
}

void write_model(const nlohmann::json& model, const std::string& path) {
  std::ofstream file(path);
  file << model.dump(1);
  if (!file.flush()) throw InputError(path, "cannot write the report's figures");
}

struct WorkFolder {
  fs::path path;
  ~WorkFolder() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

}  // namespace

void write_report(const std::vector<std::string>& inputs, const std::string& out_dir, const ReportOptions& options) {
  if (inputs.empty()) throw InputError("report", "no results file given");
  if (options.history && !options.papers.empty())
    throw InputError(options.papers.front(), "--paper belongs in a comparison report, not in --history");
  // Every input is read and checked here, before anything is written: a bad one is named in one
  // line and leaves an earlier report as it was.
  std::vector<ResultsFile> read;
  for (const auto& in : inputs) read.push_back(read_results(in));
  std::vector<ResultsFile> staged_files;
  if (options.history) staged_files = read;
  else staged_files.push_back(merge_results(read, inputs, {options.allow_mixed}));
  std::optional<std::string> pictures;
  if (!options.history) pictures = find_pictures_manifest(out_dir, inputs.front());
  if (pictures) check_pictures_manifest(*pictures);
  check_paper_tables(options.papers);

  prepare_output_folder(out_dir);
  const WorkFolder work{make_work_folder(out_dir)};
  // The script reads what this build writes: the inputs written again whole (every field present,
  // NaN as null, shards merged).
  std::vector<std::string> staged;
  for (size_t i = 0; i < staged_files.size(); ++i) {
    staged.push_back((work.path / (std::to_string(i) + ".json")).string());
    write_results(staged_files[i], staged.back());
  }
  const fs::path written = work.path / "report";
  // Debian's interpreter: python3-matplotlib lives there, not in a user's pyenv. An argument
  // vector, not a shell line: file names are data.
  std::vector<std::string> argv = {"/usr/bin/python3", resource_path("reports/report.py"), "--out", written.string(),
                                   "--schemes", registry_schemes()};
  if (options.history) {
    // The gate's figures and verdicts per commit, computed here once (history.h) with the gate's
    // own code; the script draws them.
    const std::string model = (work.path / "history.json").string();
    write_model(history_json(make_history(staged_files, read_gate_config(resource_path("ci/gate.json")))), model);
    argv.insert(argv.end(), {"--history", model, "--names"});
    argv.insert(argv.end(), inputs.begin(), inputs.end());
  } else {
    // The first screen's figures, computed here once (overview.h); the script lays them out.
    const std::string overview = (work.path / "overview.json").string();
    write_model(overview_json(make_overview(staged_files.front())), overview);
    argv.insert(argv.end(), {"--merged-from", merged_from(read), "--overview", overview});
  }
  if (pictures) argv.insert(argv.end(), {"--pictures", *pictures});
  for (const auto& p : options.papers) argv.insert(argv.end(), {"--paper", p});
  if (!options.papers_note.empty()) argv.insert(argv.end(), {"--papers-note", options.papers_note});
  argv.push_back("--");
  argv.insert(argv.end(), staged.begin(), staged.end());
  const ProcessResult r = run_process(argv);
  if (r.exit_code != 0)
    throw InputError(out_dir, "report generation failed (reports/report.py, " + r.describe() + "); an earlier report is left as it was");
  try {
    move_into_place(written, out_dir);
  } catch (const fs::filesystem_error& e) {
    throw InputError(out_dir, std::string("cannot move the report into place: ") + e.what());
  }
}

}  // namespace sdb
