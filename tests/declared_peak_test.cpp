// Each scheme's declared peak memory (SchemeInfo::peak_bytes_per_triangle, what `bench` refuses a
// run on up front) against a validated run's: `subdivbench validate` at two depths of one mesh, each
// in its own child process, and the growth of the child's maximum resident set per output triangle
// between them (the slope: the process's baseline of libraries and mesh cancels), as
// harness/bench/notes/limits-2026-12-07.md and the schemes' notes measured it. A declaration under
// the slope lets a large run past the up-front check into bad_alloc or the OOM killer.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "harness/core/registry.h"
#include "tests/cli_helpers.h"

extern char** environ;

namespace sdb {
namespace {

struct ValidatedRun {
  int exit_code = -1;
  long max_rss_kib = 0;
  double triangles = 0;
  std::string err;
};

// `subdivbench validate --json` without a shell; wait4 gives the child's own maximum RSS.
ValidatedRun validate(const std::string& scheme, const std::string& mesh, int level) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("sdb_peak_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string out = (dir / "row.json").string(), err = (dir / "err.txt").string();
  const std::string exe = std::string(SDB_BINARY_DIR) + "/subdivbench", level_text = std::to_string(level);
  std::vector<std::string> args = {exe, "validate", "--scheme", scheme, "--mesh", mesh, "--level", level_text,
                                   "--rays", "1000", "--json"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&files, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  ValidatedRun r;
  const int spawned = posix_spawn(&pid, exe.c_str(), &files, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  if (spawned != 0) return r;
  int status = 0;
  rusage usage{};
  if (wait4(pid, &status, 0, &usage) != pid) return r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.max_rss_kib = usage.ru_maxrss;
  r.err = test::slurp(err);
  const nlohmann::json row = nlohmann::json::parse(test::slurp(out), nullptr, false);
  if (row.is_object() && row.contains("triangles") && row["triangles"].is_number()) r.triangles = row["triangles"].get<double>();
  return r;
}

struct PeakCase {
  const char* scheme;
  const char* mesh;  // procedural: the same on every machine
  int small_level, large_level;
};

void PrintTo(const PeakCase& c, std::ostream* os) { *os << c.scheme << " on " << c.mesh; }

class DeclaredPeak : public ::testing::TestWithParam<PeakCase> {};

// Exit 1 is a row that ran to its end and failed a verdict: its memory is measured all the same.
TEST_P(DeclaredPeak, ValidatedRunGrowsByLessPerTriangleThanDeclared) {
  const PeakCase& c = GetParam();
  const Scheme* scheme = find_scheme(c.scheme);
  ASSERT_NE(scheme, nullptr) << c.scheme;
  const ValidatedRun small = validate(c.scheme, c.mesh, c.small_level), large = validate(c.scheme, c.mesh, c.large_level);
  for (const ValidatedRun* r : {&small, &large}) {
    ASSERT_TRUE(r->exit_code == 0 || r->exit_code == 1) << "exit " << r->exit_code << ": " << r->err;
    ASSERT_GT(r->triangles, 0) << r->err;
  }
  ASSERT_GT(large.triangles, 3 * small.triangles);
  const double slope = double(large.max_rss_kib - small.max_rss_kib) * 1024 / (large.triangles - small.triangles);
  const double declared = scheme->info().peak_bytes_per_triangle;
  std::printf("%s on %s, depth %d -> %d: %.0f -> %.0f triangles, maximum RSS %ld -> %ld KiB: %.0f bytes per triangle, "
              "declared %.0f (%.2fx)\n",
              c.scheme, c.mesh, c.small_level, c.large_level, small.triangles, large.triangles, small.max_rss_kib,
              large.max_rss_kib, slope, declared, declared / slope);
  EXPECT_GT(slope, 0);  // a run that makes four times the output holds more
  EXPECT_LE(slope, declared) << c.scheme << " declares less peak memory per triangle than a validated run takes";
}

INSTANTIATE_TEST_SUITE_P(Schemes, DeclaredPeak,
                         ::testing::Values(PeakCase{"osd-uniform", "frog-party", 2, 3},
                                           PeakCase{"osd-uniform-loop", "frog-party-triangles", 2, 3},
                                           PeakCase{"halfedge-cc", "frog-party", 2, 3},
                                           PeakCase{"halfedge-loop", "frog-party-triangles", 2, 3},
                                           PeakCase{"edgefriend-cc", "frog-party", 2, 3},
                                           PeakCase{"fragments-cc", "frog-party", 2, 3},
                                           PeakCase{"mipgh-cc", "frog-party", 2, 3}),
                         [](const ::testing::TestParamInfo<PeakCase>& i) {
                           std::string name = i.param.scheme;
                           for (char& ch : name)
                             if (ch == '-') ch = '_';
                           return name;
                         });

}  // namespace
}  // namespace sdb
