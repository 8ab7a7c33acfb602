// `subdivbench run` as one pipeline: a new run planned into its folder (or an interrupted one
// resumed from its journal), its rows measured with their progress, the summary cells timed in
// paired rounds, results.json and the report published as one set (run_set.h), and the summary
// printed. What lies above this module (the report's pictures, the report itself) comes in as
// sinks from the composition root (app/).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "harness/run/plan.h"

namespace sdb {

// Paired rounds of the summary cells when the command line gives none: the quick set's fewer.
inline constexpr int kPairedRounds = 5, kQuickPairedRounds = 3;

struct RunPipelineRequest {
  std::string out;      // the run's folder: a new run's, or the one resumed
  bool resume = false;  // continue the run journalled in `out`
  // A new run's selection (required); resumed, the one the journal must hold (nullopt: the journal's).
  std::optional<RunSelection> selection;
  bool isolate = true;  // each row in a worker process (row_worker.h); false: in this process
  bool force = false;   // replace an unfinished run's journal in `out`
  bool paired = true;   // time the summary cells in paired rounds
  std::optional<int> rounds;  // nullopt: kQuickPairedRounds for the quick set, else kPairedRounds
  bool papers = true;   // measure the registered paper tables for the report of a whole set
};

struct RunSinks {
  // The report's pictures, drawn into the publishing folder for the run's selection before the
  // paper tables are measured (empty: none).
  std::function<void(const Selection& selection, const std::string& dir)> pictures;
  // The report, written into the publishing folder from results.json and the paper tables' files,
  // or why it has none (empty: results.json alone is published).
  std::function<void(const std::string& results_json, const std::string& dir, const std::vector<std::string>& papers,
                     const std::string& papers_note)>
      report;
};

// The run: its exit code (1 when a row failed, else 0). InputError as RunSet::start and resume say.
int run_pipeline(const RunPipelineRequest& request, const RunSinks& sinks);

// `run --plan`: the rows the selection would measure, counted per backend, nothing measured or
// written (the README's counts come from here). Exit code 0.
int print_plan(const RunSelection& selection);

}  // namespace sdb
