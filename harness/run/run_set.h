// A `run` of a selection: planned, measured row by row (each in a worker process unless asked
// otherwise: row_worker.h), every row journalled as it completes (journal.h), resumable after a
// crash or a kill, and published as one set (results.json and the report) from the journal.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "harness/run/journal.h"
#include "harness/run/plan.h"
#include "harness/results/output_folder.h"

namespace sdb {

class RunSet {
 public:
  // A new run into `out`: the folder checked and locked before anything is measured (InputError
  // naming the other run's process while one writes it), the machine described with its probes,
  // the plan made, and (unless the plan is empty) a new journal started, recording the content
  // hash of every input file. An unfinished run's journal there is refused unless `force`.
  static RunSet start(const std::string& out, const RunSelection& selection, bool isolate, bool force = false);
  // The interrupted run journalled in `out`. `selection`, when given, must be the journalled one
  // (nullopt: the journal's). InputError, one line naming the journal, when the selection, the
  // commit, the machine, the working folder or the plan differ, or the journal is corrupt beyond
  // a torn last line (dropped); and naming the file when an input's content changed since.
  static RunSet resume(const std::string& out, const std::optional<RunSelection>& selection, bool isolate);

  const Plan& plan() const { return plan_; }
  const RunSelection& selection() const { return selection_; }  // the journal's, when resumed
  const MachineInfo& machine() const;
  size_t journalled() const { return journalled_; }  // rows in the journal when this run began
  bool dropped_torn_line() const { return dropped_torn_line_; }
  size_t remaining() const { return plan_.runs.size() - journalled_; }

  // Measures the rows the journal lacks, in plan order; each is journalled before on_row sees it.
  // `on_start` (may be empty) sees each run as it begins.
  void measure_remaining(const std::function<void(const RunRow&)>& on_row,
                         const std::function<void(const RunSpec&)>& on_start = {});

  // The results as the journal holds them, rows in plan order, with the selection's shard.
  ResultsFile results() const;
  // The context the rows were planned in (meshes loaded once), for measuring beside the rows.
  MeasureContext& context() { return *context_; }

  // Refused (InputError, nothing written) when nothing ran; otherwise results.json and, with
  // `report`, the report are written into `out` as one set (publish_results).
  using ReportWriter = std::function<void(const std::string& results_json, const std::string& dir)>;
  void publish(const ResultsFile& results, const ReportWriter& report) const;

  RunSet(RunSet&&) noexcept;
  ~RunSet();

 private:
  RunSet(std::string out, const MachineInfo& machine, bool isolate);
  std::string journal_path() const;

  std::string out_;
  std::unique_ptr<FolderLock> lock_;  // held from start or resume until the set is gone
  bool isolate_ = true;
  std::unique_ptr<MeasureContext> context_;
  RunSelection selection_;
  Plan plan_;
  std::optional<JournalWriter> journal_;
  std::map<std::string, int> done_;  // journalled rows by run name
  size_t journalled_ = 0;
  bool dropped_torn_line_ = false;
};

// results.json (and `report`'s files) written into a staging folder inside `dir`, then moved over
// the earlier set only once every file is written: a failure (the report, a full disk) leaves the
// earlier set as it was.
void publish_results(const ResultsFile& results, const std::string& dir, const RunSet::ReportWriter& report);

}  // namespace sdb
