// Reports: report.md and a self-contained report.html with plots, from results.json files.
#pragma once

#include <string>
#include <vector>

namespace sdb {

struct ReportOptions {
  std::vector<std::string> papers;  // Markdown written by `subdivbench paper ID`, included as they are
  // One line in the report's paper section: why it holds no table, or which tables are missing.
  std::string papers_note;
  // The inputs are one results file per commit, oldest first: the gate's view over commits
  // instead of one merged comparison.
  bool history = false;
  bool allow_mixed = false;  // merge files from different commits or machines
};

// Reads and validates every input (results files, the pictures manifest, paper tables) before
// writing anything, then runs reports/report.py (Debian's python3, matplotlib) into a temporary
// folder inside `out_dir` and moves report.md, report.html and plots/ into place only when it
// succeeded: a failure leaves an earlier report as it was. Throws InputError naming the file.
//
// Pictures: out_dir/pictures/pictures.json when present, else pictures/pictures.json beside the
// first input.
void write_report(const std::vector<std::string>& results_files, const std::string& out_dir,
                  const ReportOptions& options = {});

}  // namespace sdb
