#include "reports/report.h"

#include <filesystem>

#include "harness/bench/process.h"
#include "harness/bench/results.h"
#include "harness/core/errors.h"

namespace sdb {

void write_report(const std::vector<std::string>& inputs, const std::string& out_dir) {
  namespace fs = std::filesystem;
  fs::create_directories(out_dir);
  // The script reads what this build writes: every input is read here (refusing a bad one, or an
  // unknown schema, with its name) and written again whole, every field present, NaN as null.
  std::vector<ResultsFile> read;
  for (const auto& in : inputs) read.push_back(read_results(in));  // all read before anything is written
  const fs::path staging = fs::path(out_dir) / ".report-inputs";
  fs::create_directories(staging);
  std::vector<std::string> staged;
  for (size_t i = 0; i < read.size(); ++i) {
    staged.push_back((staging / (std::to_string(i) + ".json")).string());
    write_results(read[i], staged.back());
  }
  // Debian's interpreter: python3-matplotlib lives there, not in a user's pyenv. An argument
  // vector, not a shell line: file names are data.
  std::vector<std::string> argv = {"/usr/bin/python3", SDB_SOURCE_DIR "/reports/report.py", "--out", out_dir, "--"};
  argv.insert(argv.end(), staged.begin(), staged.end());
  const ProcessResult r = run_process(argv);
  std::error_code ec;
  fs::remove_all(staging, ec);
  if (r.exit_code != 0) throw InputError(out_dir, "report generation failed (reports/report.py, " + r.describe() + ")");
}

}  // namespace sdb
