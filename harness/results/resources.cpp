#include "harness/results/resources.h"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>

namespace sdb {
namespace {

const char* home() {
  const char* h = std::getenv(kHomeVariable);
  return h && *h ? h : nullptr;
}

// A fixed command line (no data in it), run through the shell for its redirections.
std::string first_line_of(const char* command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command, "r"), pclose);
  if (!pipe) return "";
  std::array<char, 256> buf{};
  if (!fgets(buf.data(), buf.size(), pipe.get())) return "";
  std::string s = buf.data();
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
  return s;
}

}  // namespace

std::string resource_path(const std::string& relative) {
  return (std::filesystem::path(home() ? home() : SDB_SOURCE_DIR) / relative).string();
}

std::string build_commit() {
  if (const char* h = home()) {
    std::ifstream in(std::filesystem::path(h) / kCommitFile);
    std::string commit;
    std::getline(in, commit);
    return commit;
  }
  std::string commit = first_line_of("git -C " SDB_SOURCE_DIR " rev-parse --short HEAD 2>/dev/null");
  if (!first_line_of("git -C " SDB_SOURCE_DIR " status --porcelain --untracked-files=no 2>/dev/null").empty())
    commit += "-dirty";
  return commit;
}

}  // namespace sdb
