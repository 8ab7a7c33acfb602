#include "report.h"

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>

#include "errors.h"

namespace sdb {
namespace {

std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

void write_report(const std::vector<std::string>& inputs, const std::string& out_dir) {
  std::filesystem::create_directories(out_dir);
  // Debian's interpreter: python3-matplotlib lives there, not in a user's pyenv.
  std::string cmd = "/usr/bin/python3 " + quoted(SDB_SOURCE_DIR "/reports/report.py") + " --out " + quoted(out_dir);
  for (const auto& in : inputs) cmd += " " + quoted(in);
  const int status = std::system(cmd.c_str());
  if (status != 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw InputError(out_dir, "report generation failed (reports/report.py)");
}

}  // namespace sdb
