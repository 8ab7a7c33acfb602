// Reports: report.md and a self-contained report.html with plots, from results.json files.
#pragma once

#include <string>
#include <vector>

namespace sdb {

// Runs reports/report.py with Debian's python3 (matplotlib); throws InputError on failure.
void write_report(const std::vector<std::string>& results_files, const std::string& out_dir);

}  // namespace sdb
