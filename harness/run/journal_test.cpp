// The run journal (journal.h) and the publishing of a set (run_set.h): what a kill, a torn write or
// a failing report leaves behind, without measuring anything.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <functional>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "harness/run/journal.h"
#include "harness/run/run_set.h"
#include "harness/core/errors.h"

using namespace sdb;
namespace fs = std::filesystem;

namespace {

fs::path fresh_folder(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("sdb_journal_test_" + std::to_string(getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

JournalHeader header() {
  JournalHeader h;
  h.machine.cpu_model = "test cpu";
  h.machine.git_commit = "abc1234";
  h.created = "2026-01-01T00:00:00Z";
  h.cwd = "/somewhere";
  h.selection.selection.schemes = {"osd-bfr", "osd-uniform"};
  h.selection.selection.levels = {2, 3};
  h.selection.reps = 2;
  h.runs = {"osd-bfr/cpu/cube/2", "osd-bfr/cpu/cube/3", "osd-uniform/cpu/cube/2"};
  return h;
}

RunRow row(const std::string& scheme, int level) {
  RunRow r;
  r.scheme = r.spec = scheme;
  r.mesh = "cube";
  r.level = level;
  r.triangles = 96 * level;
  r.deviation.measured = true;
  r.deviation.pos_max_pct = 0.5 * level;
  return r;
}

std::string expect_input_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

}  // namespace

TEST(Journal, HeaderAndRowsReadBackAsWritten) {
  const fs::path path = fresh_folder("roundtrip") / kJournalFile;
  {
    JournalWriter w = JournalWriter::create(path.string(), header());
    w.append(row("osd-bfr", 2));
    w.append(row("osd-bfr", 3));
  }
  const JournalContents c = read_journal(path.string());
  EXPECT_TRUE(c.header.selection == header().selection);
  EXPECT_EQ(c.header.runs, header().runs);
  EXPECT_EQ(c.header.machine.git_commit, "abc1234");
  EXPECT_EQ(c.header.cwd, "/somewhere");
  ASSERT_EQ(c.rows.size(), 2u);
  EXPECT_EQ(c.rows[1].name(), "osd-bfr/cpu/cube/3");
  EXPECT_EQ(c.rows[1].triangles, 288);
  EXPECT_EQ(c.row_lines, (std::vector<int>{2, 3}));
  EXPECT_FALSE(c.dropped_torn_line);
  EXPECT_EQ(c.intact_bytes, fs::file_size(path));
  // One line per row: a reader (or a person) can count rows with wc -l.
  const std::string text = slurp(path);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 3);
}

// NaN and infinities have no JSON spelling: they are written as null and read back as NaN,
// "not measured", in the journal as in results.json.
TEST(Journal, NonFiniteFiguresAreNullAndReadBackAsNaN) {
  const fs::path path = fresh_folder("nonfinite") / kJournalFile;
  RunRow r = row("osd-bfr", 2);
  r.deviation.pos_max_pct = std::numeric_limits<double>::quiet_NaN();
  r.deviation.pos_p95_pct = std::numeric_limits<double>::infinity();
  r.deviation.pos_mean_pct = 0.25;
  r.time_ms.samples = {1.0, -std::numeric_limits<double>::infinity()};
  JournalWriter::create(path.string(), header()).append(r);
  EXPECT_NE(slurp(path).find("\"pos_max_pct\":null"), std::string::npos) << slurp(path);
  const RunRow back = read_journal(path.string()).rows.at(0);
  EXPECT_TRUE(std::isnan(back.deviation.pos_max_pct));
  EXPECT_TRUE(std::isnan(back.deviation.pos_p95_pct));
  EXPECT_EQ(back.deviation.pos_mean_pct, 0.25) << "a NaN maximum does not take the finite figures with it";
  EXPECT_TRUE(std::isnan(back.time_ms.samples.at(1)));
  EXPECT_EQ(back.triangles, 192);
}

// A kill or a full disk mid-write leaves a last line without its newline: dropped, and cut off
// before the next row is appended, so that the journal reads whole again.
TEST(Journal, TornLastLineIsDroppedAndCutBeforeAppending) {
  const fs::path path = fresh_folder("torn") / kJournalFile;
  JournalWriter::create(path.string(), header()).append(row("osd-bfr", 2));
  const auto whole = fs::file_size(path);
  const std::string next = row_json(row("osd-bfr", 3), -1);
  std::ofstream(path, std::ios::app) << next.substr(0, next.size() / 2);
  JournalContents c = read_journal(path.string());
  EXPECT_EQ(c.rows.size(), 1u);
  EXPECT_TRUE(c.dropped_torn_line);
  EXPECT_EQ(c.intact_bytes, whole);
  JournalWriter::reopen(path.string(), c.intact_bytes).append(row("osd-uniform", 2));
  c = read_journal(path.string());
  ASSERT_EQ(c.rows.size(), 2u);
  EXPECT_EQ(c.rows[1].name(), "osd-uniform/cpu/cube/2");
  EXPECT_FALSE(c.dropped_torn_line);
}

// A full disk mid-row (here a file-size limit, which fails write() the same way): the row is
// refused with the journal named, and the journal is cut back to its last whole row.
TEST(Journal, AFullDiskLosesOnlyTheRowInFlight) {
  const fs::path path = fresh_folder("full") / kJournalFile;
  JournalWriter w = JournalWriter::create(path.string(), header());
  w.append(row("osd-bfr", 2));
  const auto whole = fs::file_size(path);
  rlimit before{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &before), 0);
  std::signal(SIGXFSZ, SIG_IGN);  // write() fails with EFBIG instead
  rlimit full = before;
  full.rlim_cur = whole + 100;  // room for part of the next row
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &full), 0);
  const std::string why = expect_input_error([&] { w.append(row("osd-bfr", 3)); });
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &before), 0);
  EXPECT_NE(why.find(path.string() + ": cannot journal row osd-bfr/cpu/cube/3: File too large"), std::string::npos) << why;
  EXPECT_EQ(fs::file_size(path), whole);
  w.append(row("osd-uniform", 2));  // room again: the run could go on
  const JournalContents c = read_journal(path.string());
  ASSERT_EQ(c.rows.size(), 2u);
  EXPECT_EQ(c.rows[1].name(), "osd-uniform/cpu/cube/2");
  EXPECT_FALSE(c.dropped_torn_line);
}

TEST(Journal, CorruptionBeforeTheLastLineIsRefusedWithItsLine) {
  const fs::path path = fresh_folder("corrupt") / kJournalFile;
  {
    JournalWriter w = JournalWriter::create(path.string(), header());
    w.append(row("osd-bfr", 2));
  }
  std::ofstream(path, std::ios::app) << "{\"scheme\": \"osd-bfr\", \"mesh\": \n" << row_json(row("osd-bfr", 3), -1) << "\n";
  const std::string why = expect_input_error([&] { read_journal(path.string()); });
  EXPECT_NE(why.find(path.string() + ":3: corrupt journal row"), std::string::npos) << why;
  EXPECT_EQ(why.find('\n'), std::string::npos) << why;
}

TEST(Journal, OtherFilesAreNotJournals) {
  const fs::path dir = fresh_folder("other");
  EXPECT_NE(expect_input_error([&] { read_journal((dir / kJournalFile).string()); }).find("no journal here"), std::string::npos);
  std::ofstream(dir / "results.json") << "{\"schema\": 1, \"runs\": []}\n";
  const std::string why = expect_input_error([&] { read_journal((dir / "results.json").string()); });
  EXPECT_NE(why.find("results.json:1: not a subdivbench run journal"), std::string::npos) << why;
  std::ofstream(dir / "half.jsonl") << "{\"journal\": 1, \"sch";
  EXPECT_NE(expect_input_error([&] { read_journal((dir / "half.jsonl").string()); }).find("half.jsonl:1:"), std::string::npos);
}

TEST(Journal, SelectionDifferenceNamesTheField) {
  RunSelection a = header().selection, b = a;
  EXPECT_EQ(selection_difference(a, b), "");
  b.reps = 3;
  EXPECT_EQ(selection_difference(a, b), "reps: journalled 2, now 3");
  b = a;
  b.selection.schemes = {"osd-bfr"};
  EXPECT_EQ(selection_difference(a, b), "schemes: journalled [\"osd-bfr\",\"osd-uniform\"], now [\"osd-bfr\"]");
}

namespace {

ResultsFile results_with(const std::string& cpu) {
  ResultsFile r;
  r.machine.cpu_model = cpu;
  r.runs.push_back(row("osd-bfr", 2));
  return r;
}

void earlier_set(const fs::path& dir) {
  std::ofstream(dir / "results.json") << "earlier results\n";
  std::ofstream(dir / "report.md") << "earlier report\n";
  fs::create_directories(dir / "plots");
  std::ofstream(dir / "plots" / "rate_cube.png") << "earlier plot";
  // What a publish records of the files it put there; a file it does not list is the user's.
  std::ofstream(dir / "plots" / ".subdivbench-files") << "rate_cube.png\n";
  std::ofstream(dir / "plots" / "mine.png") << "the user's plot";
}

}  // namespace

TEST(Publish, ReplacesTheEarlierSetWhole) {
  const fs::path dir = fresh_folder("publish");
  earlier_set(dir);
  publish_results(results_with("new cpu"), dir.string(), [](const std::string& results, const std::string& out) {
    EXPECT_NE(slurp(results).find("new cpu"), std::string::npos) << "the report reads the new results";
    std::ofstream(fs::path(out) / "report.md") << "new report\n";
    fs::create_directories(fs::path(out) / "plots");
    std::ofstream(fs::path(out) / "plots" / "rate_torus.png") << "new plot";
  });
  EXPECT_EQ(read_results((dir / "results.json").string()).machine.cpu_model, "new cpu");
  EXPECT_EQ(slurp(dir / "report.md"), "new report\n");
  EXPECT_TRUE(fs::exists(dir / "plots" / "rate_torus.png"));
  EXPECT_FALSE(fs::exists(dir / "plots" / "rate_cube.png")) << "a plot of the earlier set left beside the new ones";
  EXPECT_EQ(slurp(dir / "plots" / "mine.png"), "the user's plot") << "a file of the user's removed";
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_NE(e.path().filename().string()[0], '.') << "staging left behind: " << e.path();
}

TEST(Publish, AFailingReportLeavesTheEarlierSetAsItWas) {
  const fs::path dir = fresh_folder("publish_fails");
  earlier_set(dir);
  const std::string why = expect_input_error([&] {
    publish_results(results_with("new cpu"), dir.string(), [](const std::string&, const std::string& out) {
      std::ofstream(fs::path(out) / "report.md") << "half a report";
      throw InputError(out, "report generation failed");
    });
  });
  EXPECT_NE(why.find("nothing replaced"), std::string::npos) << why;
  EXPECT_EQ(slurp(dir / "results.json"), "earlier results\n");
  EXPECT_EQ(slurp(dir / "report.md"), "earlier report\n");
  EXPECT_TRUE(fs::exists(dir / "plots" / "rate_cube.png"));
  EXPECT_FALSE(fs::exists(dir / ".publishing"));
}
