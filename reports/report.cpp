#include "reports/report.h"

#include <filesystem>

#include "harness/bench/process.h"
#include "harness/core/errors.h"

namespace sdb {

void write_report(const std::vector<std::string>& inputs, const std::string& out_dir) {
  std::filesystem::create_directories(out_dir);
  // Debian's interpreter: python3-matplotlib lives there, not in a user's pyenv. An argument
  // vector, not a shell line: file names are data.
  std::vector<std::string> argv = {"/usr/bin/python3", SDB_SOURCE_DIR "/reports/report.py", "--out", out_dir, "--"};
  argv.insert(argv.end(), inputs.begin(), inputs.end());
  const ProcessResult r = run_process(argv);
  if (r.exit_code != 0) throw InputError(out_dir, "report generation failed (reports/report.py, " + r.describe() + ")");
}

}  // namespace sdb
