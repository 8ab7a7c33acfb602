// run's journal end to end: a run killed with SIGKILL mid-run and resumed gives the rows an
// uninterrupted run gives (all but the timings), and a resume under another selection is refused.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <thread>

#include "tests/cli_helpers.h"

extern char** environ;

namespace fs = std::filesystem;
using nlohmann::json;
using sdb::test::run_cli;
using sdb::test::slurp;

namespace {

// Two fast schemes on two built-in meshes at two levels: 8 rows of a fraction of a second each.
const std::string kSelection =
    "--scheme osd-bfr --scheme osd-uniform --mesh cube --mesh torus-8x8 --level 2 --level 3 --backend cpu "
    "--reps 2 --rays 5000";
constexpr int kRows = 8;

fs::path fresh_folder(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("sdb_resume_" + std::to_string(getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  return dir;
}

// subdivbench started in the background (an argument vector, stdout and stderr to files).
pid_t start_cli(const std::vector<std::string>& args, const fs::path& log) {
  std::vector<std::string> argv = {std::string(SDB_BINARY_DIR) + "/subdivbench"};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> c;
  for (auto& a : argv) c.push_back(a.data());
  c.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = -1;
  EXPECT_EQ(posix_spawn(&pid, c[0], &actions, nullptr, c.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

// Rows the journal holds: its complete lines after the header.
int journalled_rows(const fs::path& journal) {
  const std::string text = slurp(journal);
  const long lines = std::count(text.begin(), text.end(), '\n');
  return lines > 0 ? int(lines - 1) : 0;
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> v;
  std::istringstream in(s);
  for (std::string w; in >> w;) v.push_back(w);
  return v;
}

// A row without what varies from run to run: its timings and what is computed from them.
json without_timings(json row) {
  for (const char* key : {"time_ms", "gpu_time_ms", "upload_ms", "readback_ms", "gpu_passes", "triangle_rate_mtris",
                          "bandwidth_fraction"})
    row.erase(key);
  return row;
}

json rows_in(const std::string& results_json) {
  const json j = json::parse(results_json);
  json rows = json::array();
  for (const json& r : j.at("runs")) rows.push_back(without_timings(r));
  return rows;
}

json rows_of(const fs::path& results) { return rows_in(slurp(results)); }

}  // namespace

TEST(Resume, KilledMidRunAndResumedGivesTheUninterruptedRows) {
  const fs::path killed = fresh_folder("killed"), whole = fresh_folder("whole");
  std::vector<std::string> args = split("run " + kSelection);
  args.insert(args.end(), {"--out", killed.string(), "--no-report"});
  const pid_t pid = start_cli(args, fs::path(killed.string() + ".log"));
  ASSERT_GT(pid, 0);
  // Killed as soon as the journal holds a row: the rest (seven rows of at least 0.1 s of timing
  // each) is still to come.
  const fs::path journal = killed / "journal.jsonl";
  int status = 0;
  bool exited = false;
  for (auto until = std::chrono::steady_clock::now() + std::chrono::seconds(120);
       std::chrono::steady_clock::now() < until && journalled_rows(journal) < 1;) {
    if (waitpid(pid, &status, WNOHANG) == pid) {
      exited = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_FALSE(exited) << "run ended before the kill:\n" << slurp(killed.string() + ".log");
  ASSERT_EQ(kill(pid, SIGKILL), 0);
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
  const int before = journalled_rows(journal);
  ASSERT_GE(before, 1);
  ASSERT_LT(before, kRows) << "the kill came after the last row";
  EXPECT_FALSE(fs::exists(killed / "results.json")) << "results.json is written at the end only";

  const auto resumed = run_cli("run --resume " + killed.string());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.out << resumed.err;
  EXPECT_NE(resumed.out.find("resuming " + killed.string() + ": " + std::to_string(before) + " of 8 rows journalled"),
            std::string::npos)
      << resumed.out;
  EXPECT_NE(resumed.out.find("measuring " + std::to_string(kRows - before) + "\n"), std::string::npos) << resumed.out;
  long measured = 0;
  for (const auto& line : split(resumed.out)) measured += line.rfind("osd-", 0) == 0 && line.find("/cpu/") != std::string::npos;
  EXPECT_EQ(measured, kRows - before) << "the resumed run measures only the rows the journal lacks:\n" << resumed.out;
  EXPECT_TRUE(fs::exists(killed / "report.md")) << "results.json and the report are written as one set";

  // The uninterrupted run measures in this process: the isolated rows above must equal these.
  const auto reference = run_cli("run " + kSelection + " --out " + whole.string() + " --no-report --in-process");
  ASSERT_EQ(reference.exit_code, 0) << reference.out << reference.err;
  const json got = rows_of(killed / "results.json"), want = rows_of(whole / "results.json");
  ASSERT_EQ(got.size(), size_t(kRows));
  ASSERT_EQ(want.size(), size_t(kRows));
  for (size_t i = 0; i < want.size(); ++i) EXPECT_EQ(got[i], want[i]) << "row " << i;
  for (const json& r : got) {
    EXPECT_EQ(r.at("status"), "ok") << r.dump();
    EXPECT_GT(r.at("triangles").get<long>(), 0) << r.dump();
  }
}

TEST(Resume, RefusesAnotherSelectionAndAJournalCorruptBeforeItsEnd) {
  const fs::path dir = fresh_folder("refusals");
  const std::string small = "--scheme osd-uniform --mesh cube --level 1 --backend cpu --reps 1 --rays 100 --no-report";
  ASSERT_EQ(run_cli("run " + small + " --out " + dir.string()).exit_code, 0);
  const std::string results = slurp(dir / "results.json");

  const auto other = run_cli("run --resume " + dir.string() + " --scheme osd-bfr --mesh cube --level 2");
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_NE(other.err.find(dir.string() + "/journal.jsonl: the interrupted run had another selection (schemes"), std::string::npos)
      << other.err;
  EXPECT_EQ(std::count(other.err.begin(), other.err.end(), '\n'), 1) << other.err;

  // The same selection spelled again, or none: a finished run resumes to the same results.
  const auto same = run_cli("run --resume " + dir.string() + " " + small);
  EXPECT_EQ(same.exit_code, 0) << same.err;
  EXPECT_NE(same.out.find("1 of 1 rows journalled; measuring 0"), std::string::npos) << same.out;
  EXPECT_EQ(rows_of(dir / "results.json"), rows_in(results));

  // A line cut short at the end is dropped and measured again; one before the end is refused.
  const fs::path journal = dir / "journal.jsonl";
  const std::string text = slurp(journal);
  const size_t row_start = text.find('\n') + 1;
  std::ofstream(journal, std::ios::trunc) << text.substr(0, text.size() - 10);
  const auto torn = run_cli("run --resume " + dir.string());
  EXPECT_EQ(torn.exit_code, 0) << torn.err;
  EXPECT_NE(torn.out.find("0 of 1 rows journalled (a torn last line dropped); measuring 1"), std::string::npos) << torn.out;
  EXPECT_EQ(journalled_rows(journal), 1);
  std::ofstream(journal, std::ios::trunc) << text.substr(0, row_start) << "{\"scheme\": 3}\n" << text.substr(row_start);
  const auto corrupt = run_cli("run --resume " + dir.string());
  EXPECT_EQ(corrupt.exit_code, 2);
  EXPECT_NE(corrupt.err.find(journal.string() + ":2: corrupt journal row"), std::string::npos) << corrupt.err;
  EXPECT_EQ(std::count(corrupt.err.begin(), corrupt.err.end(), '\n'), 1) << corrupt.err;
}
