// The performance gate end to end: the project passes against its own baseline twice in a row,
// and fails when a 2x slowdown is planted in one scheme — by time with the U test, and by
// callgrind's instruction count. The plant is the test scheme's own ($SDB_BILINEAR_SLOWDOWN,
// tests/schemes/bilinear), run through subdivbench-testing: the product's benchmark loop has no
// hook for it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli_helpers.h"

namespace fs = std::filesystem;

namespace {

sdb::test::CliResult run_cli(const std::string& args, const std::string& env = "") {
  return sdb::test::run_cli(args, env, "subdivbench-testing");
}

// The anchor (osd-bfr, normalised by the write probe), a peer paired with it, and the test scheme
// paired with it: all at 8 segments per edge on the frog stand-in.
const std::string kRuns = "--run osd-bfr/cpu/frog-standin/9 --run bilinear-limit/cpu/frog-standin/9 "
                          "--run osd-uniform/cpu/frog-standin/3";
// Nine rounds, each benchmark once per round in random order: the gate pairs samples by round.
const std::string kFlags = "--rounds 9 --benchmark_min_time=0.02";
const std::string kSlow = "SDB_BILINEAR_SLOWDOWN=2";

// The test checks the mechanism on whatever machine runs the suite, which may be shared: a 50%
// threshold still catches the planted 2x with margin. ci/gate.json keeps the production 25%.
std::string test_config() {
  const fs::path p = fs::temp_directory_path() / "sdb_gate_test_config.json";
  // The anchor gets 100% as in ci/gate.json: it is normalised by the write probe, which drifts.
  std::ofstream(p) << R"({"alpha": 0.05, "min_repetitions": 9, "default_threshold": 0.5,
                          "thresholds": [{"match": "^osd-bfr/", "threshold": 1.0}],
                          "callgrind": {"threshold": 0.02,
                                        "workloads": ["osd-bfr/cpu/torus-8x8/5", "bilinear-limit/cpu/torus-8x8/5"]}})";
  return p.string();
}

std::string bench_into(const std::string& name, const std::string& env = "") {
  const fs::path dir = fs::temp_directory_path() / ("sdb_gate_" + name);
  const auto r = run_cli("bench " + kRuns + " --out " + dir.string() + " " + kFlags, env);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return (dir / "results.json").string();
}

std::string line_of(const std::string& out, const std::string& name) {
  const size_t at = out.find(name);
  return at == std::string::npos ? "" : out.substr(at, out.find('\n', at) - at);
}

}  // namespace

TEST(Gate, PassesTwiceInARowAndFailsOnAPlantedSlowdown) {
  const std::string base = bench_into("base"), again1 = bench_into("again1"), again2 = bench_into("again2");
  const std::string slow = bench_into("slow", kSlow);
  for (const auto& current : {again1, again2}) {
    const auto r = run_cli("gate --config " + test_config() + " --baseline " + base + " --current " + current);
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_EQ(r.out.find("REGRESSION"), std::string::npos) << r.out;
  }
  const auto r = run_cli("gate --config " + test_config() + " --baseline " + base + " --current " + slow);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  // Only the slowed scheme moved: its line says REGRESSION (normalised by its peer), the others' do not.
  const std::string slowed = line_of(r.out, "bilinear-limit/cpu/frog-standin/9");
  EXPECT_NE(slowed.find("REGRESSION"), std::string::npos) << r.out;
  EXPECT_NE(slowed.find("osd-bfr, paired"), std::string::npos) << r.out;
  EXPECT_EQ(line_of(r.out, "osd-uniform/cpu/frog-standin/3").find("REGRESSION"), std::string::npos) << r.out;
}

TEST(Gate, RefusesTooFewRepetitions) {
  const fs::path dir = fs::temp_directory_path() / "sdb_gate_few";
  ASSERT_EQ(run_cli("bench --run osd-bfr/cpu/torus-8x8/5 --out " + dir.string() + " --benchmark_repetitions=3").exit_code, 0);
  const std::string f = (dir / "results.json").string();
  const auto r = run_cli("gate --baseline " + f + " --current " + f);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("the gate needs 9"), std::string::npos) << r.out;
}

TEST(Gate, CallgrindCountsAreDeterministicAndCatchThePlant) {
  if (std::system("valgrind --version >/dev/null 2>&1") != 0) GTEST_SKIP() << "valgrind not installed";
  const fs::path counts = fs::temp_directory_path() / "sdb_callgrind_baseline.json";
  const std::string config = " --config " + test_config();
  const auto recorded = run_cli("gate --callgrind --record --baseline " + counts.string() + config);
  // valgrind's own limit on this machine (callgrind.h, valgrind_unusable): said, and skipped
  if (recorded.exit_code == 2 && recorded.err.find("valgrind cannot run") != std::string::npos)
    GTEST_SKIP() << recorded.err;
  ASSERT_EQ(recorded.exit_code, 0) << recorded.err;
  const auto same = run_cli("gate --callgrind --baseline " + counts.string() + config);
  EXPECT_EQ(same.exit_code, 0) << same.out << same.err;
  // Deterministic to a few instructions in millions (a fresh clone's run measured 4 in 4 M): the
  // change prints as +0.00% or -0.00%.
  EXPECT_NE(line_of(same.out, "bilinear-limit/cpu/torus-8x8/5").find("0.00%"), std::string::npos) << same.out;
  const auto slow = run_cli("gate --callgrind --baseline " + counts.string() + config, kSlow);
  EXPECT_EQ(slow.exit_code, 1) << slow.out;
  EXPECT_NE(line_of(slow.out, "bilinear-limit/cpu/torus-8x8/5").find("REGRESSION"), std::string::npos) << slow.out;
  EXPECT_EQ(line_of(slow.out, "osd-bfr/cpu/torus-8x8/5").find("REGRESSION"), std::string::npos) << slow.out;
}

// Where valgrind cannot run subdivbench (it stops with SIGILL, as on the AMD EPYC CI machine), the
// comparison is skipped and said with exit 0, so the timing gate alone decides; recording still
// fails with one line. A stand-in valgrind that stops itself with SIGILL makes that machine here.
TEST(Gate, CallgrindComparisonIsSkippedWhereValgrindCannotRun) {
  const fs::path bin = fs::temp_directory_path() / "sdb_sigill_valgrind";
  fs::create_directories(bin);
  std::ofstream(bin / "valgrind") << "#!/bin/sh\nkill -ILL $$\n";
  fs::permissions(bin / "valgrind", fs::perms::owner_all);
  const std::string env = "PATH=" + bin.string() + ":$PATH";
  const fs::path counts = fs::temp_directory_path() / "sdb_callgrind_sigill.json";
  std::ofstream(counts) << R"({"osd-bfr/cpu/torus-8x8/5": 1000, "bilinear-limit/cpu/torus-8x8/5": 1000})";
  const std::string config = " --config " + test_config();
  const auto compared = run_cli("gate --callgrind --baseline " + counts.string() + config, env);
  EXPECT_EQ(compared.exit_code, 0) << compared.out << compared.err;
  EXPECT_NE(compared.out.find("instruction counts not compared: valgrind cannot run"), std::string::npos) << compared.out;
  EXPECT_EQ(compared.out.find("REGRESSION"), std::string::npos) << compared.out;
  const auto recorded = run_cli("gate --callgrind --record --baseline " + counts.string() + config, env);
  EXPECT_EQ(recorded.exit_code, 2) << recorded.out << recorded.err;
  EXPECT_NE(recorded.err.find("valgrind cannot run"), std::string::npos) << recorded.err;
}
