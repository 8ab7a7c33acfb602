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

namespace {

// Waits until the run `pid` has started a journal of its own (not `earlier`) that holds `rows`
// rows (true), or ends first (false).
bool wait_for_rows(pid_t pid, const fs::path& journal, int rows, const std::string& earlier = "") {
  int status = 0;
  for (auto until = std::chrono::steady_clock::now() + std::chrono::seconds(120); std::chrono::steady_clock::now() < until;) {
    if (journalled_rows(journal) >= rows && (earlier.empty() || slurp(journal) != earlier)) return true;
    if (waitpid(pid, &status, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

int exit_code_of(pid_t pid) {
  int status = 0;
  EXPECT_EQ(waitpid(pid, &status, 0), pid);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

const std::string kCube = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                          "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

}  // namespace

// Issue 40: a resumed run whose mesh file changed content at the same path would publish rows of
// two meshes as one; the journal records each input's content hash and resume refuses, naming it.
TEST(Resume, RefusesAnInputFileWhoseContentChanged) {
  const fs::path dir = fresh_folder("changed-input");
  fs::create_directories(dir);
  const fs::path mesh = dir / "box.obj";
  std::ofstream(mesh) << kCube;
  const std::string selection = "--scheme osd-uniform --mesh " + mesh.string() + " --level 1 --level 2 --backend cpu --reps 1 --rays 100 --no-report";
  ASSERT_EQ(run_cli("run " + selection + " --out " + (dir / "out").string()).exit_code, 0);
  const std::string header = slurp(dir / "out" / "journal.jsonl").substr(0, slurp(dir / "out" / "journal.jsonl").find('\n'));
  EXPECT_NE(header.find("\"inputs\":[{\"hash\":"), std::string::npos) << header;
  EXPECT_EQ(run_cli("run --resume " + (dir / "out").string()).exit_code, 0) << "unchanged, it resumes";

  std::ofstream(mesh, std::ios::trunc) << kCube << "v 2 2 2\nf 7 6 9\n";  // another mesh, same path
  const auto changed = run_cli("run --resume " + (dir / "out").string());
  EXPECT_EQ(changed.exit_code, 2) << changed.out;
  EXPECT_EQ(changed.err.find("subdivbench: " + mesh.string() + ": changed since " + (dir / "out" / "journal.jsonl").string() +
                             " recorded it"),
            0u)
      << changed.err;
  EXPECT_EQ(std::count(changed.err.begin(), changed.err.end(), '\n'), 1) << changed.err;
}

// Issue 40: a second run into a folder a run is writing is refused, naming the first run's
// process, and the first run finishes whole; a run that was killed leaves an unfinished journal
// that a new run replaces only with --force, saying so.
TEST(Run, OneRunWritesAFolderAtATimeAndAnUnfinishedJournalIsKept) {
  const fs::path dir = fresh_folder("locked");
  std::vector<std::string> args = split("run " + kSelection);
  args.insert(args.end(), {"--out", dir.string(), "--no-report"});
  const pid_t first = start_cli(args, fs::path(dir.string() + ".first.log"));
  ASSERT_TRUE(wait_for_rows(first, dir / "journal.jsonl", 1)) << slurp(dir.string() + ".first.log");
  const std::string small = " --scheme osd-uniform --mesh cube --level 1 --backend cpu --reps 1 --rays 100 --no-report";
  const auto second = run_cli("run" + small + " --out " + dir.string());
  EXPECT_EQ(second.exit_code, 2);
  EXPECT_NE(second.err.find(dir.string() + ": another run (process " + std::to_string(first) + ") is writing this folder"),
            std::string::npos)
      << second.err;
  EXPECT_EQ(std::count(second.err.begin(), second.err.end(), '\n'), 1) << second.err;
  ASSERT_EQ(exit_code_of(first), 0) << slurp(dir.string() + ".first.log");
  EXPECT_EQ(rows_of(dir / "results.json").size(), size_t(kRows)) << "the first run's rows were lost";

  // Killed after a row: its journal is an unfinished run.
  const std::string finished = slurp(dir / "journal.jsonl");
  const pid_t killed = start_cli(args, fs::path(dir.string() + ".killed.log"));
  ASSERT_TRUE(wait_for_rows(killed, dir / "journal.jsonl", 1, finished));
  ASSERT_EQ(kill(killed, SIGKILL), 0);
  exit_code_of(killed);
  const int journalled = journalled_rows(dir / "journal.jsonl");
  ASSERT_LT(journalled, kRows);
  const std::string unfinished = slurp(dir / "journal.jsonl");
  const auto refused = run_cli("run" + small + " --out " + dir.string());
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find((dir / "journal.jsonl").string() + ": holds an unfinished run (" + std::to_string(journalled) +
                             " of 8 rows"),
            std::string::npos)
      << refused.err;
  EXPECT_EQ(slurp(dir / "journal.jsonl"), unfinished) << "the unfinished journal was touched";
  const auto forced = run_cli("run" + small + " --force --out " + dir.string());
  EXPECT_EQ(forced.exit_code, 0) << forced.err;
  EXPECT_NE(forced.out.find("holds an unfinished run (" + std::to_string(journalled) + " of 8 rows"), std::string::npos)
      << forced.out;
  EXPECT_NE(forced.out.find("replaced (--force)"), std::string::npos) << forced.out;
}

// Issue 40: run --out DIR publishes its files over its earlier ones only: a file of the user's in
// DIR, DIR/plots or DIR/pictures stays.
TEST(Run, KeepsTheUsersFilesInTheOutputFolder) {
  const fs::path dir = fresh_folder("users-files");
  fs::create_directories(dir / "plots");
  fs::create_directories(dir / "pictures");
  std::ofstream(dir / "plots" / "mine.png") << "my plot";
  std::ofstream(dir / "pictures" / "mine.txt") << "my notes";
  std::ofstream(dir / "notes.txt") << "more notes";
  const auto r = run_cli("run --scheme osd-uniform --mesh cube --level 1 --level 2 --backend cpu --reps 1 --rays 100 --no-paired --out " +
                         dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "plots" / "rate.png"));
  EXPECT_EQ(slurp(dir / "plots" / "mine.png"), "my plot");
  EXPECT_EQ(slurp(dir / "pictures" / "mine.txt"), "my notes");
  EXPECT_EQ(slurp(dir / "notes.txt"), "more notes");
}

// Issue 40: a selection that names a run twice measures it once; the set publishes and resumes.
TEST(Run, ASelectionNamingARunTwiceMeasuresItOnce) {
  const fs::path dir = fresh_folder("twice");
  const std::string selection =
      "--scheme osd-uniform --scheme osd-uniform --mesh cube --mesh cube --level 1 --level 1 --backend cpu --reps 1 --rays 100 --no-report";
  const auto r = run_cli("run " + selection + " --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("osd-uniform/cpu/cube/1 is named more than once: measured once"), std::string::npos) << r.out;
  EXPECT_EQ(rows_of(dir / "results.json").size(), 1u);
  const auto resumed = run_cli("run --resume " + dir.string());
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(rows_of(dir / "results.json").size(), 1u);
}
