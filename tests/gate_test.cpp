// The performance gate end to end: the project passes against its own baseline twice in a row,
// and fails when a 2x slowdown is planted in one scheme (SUBDIVBENCH_PLANT_SLOWDOWN, read only by
// the benchmark loop for this test) — by time with the U test, and by callgrind's instruction count.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli_helpers.h"

namespace fs = std::filesystem;
using sdb::test::run_cli;

namespace {

const std::string kRuns =
    "--run osd-bfr/cpu/frog-standin/9 --run embree-subdiv/cpu/frog-standin/9 --run osd-uniform/cpu/frog-standin/3";
// Nine rounds, each benchmark once per round in random order: the gate pairs samples by round.
const std::string kFlags = "--rounds 9 --benchmark_min_time=0.02";

// The test checks the mechanism on whatever machine runs the suite, which may be shared: a 50%
// threshold still catches the planted 2x with margin. ci/gate.json keeps the production 25%.
std::string test_config() {
  const fs::path p = fs::temp_directory_path() / "sdb_gate_test_config.json";
  // The anchor gets 100% as in ci/gate.json: it is normalised by the write probe, which drifts.
  std::ofstream(p) << R"({"alpha": 0.05, "min_repetitions": 9, "default_threshold": 0.5,
                          "thresholds": [{"match": "^osd-bfr/", "threshold": 1.0}]})";
  return p.string();
}

std::string bench_into(const std::string& name, const std::string& env = "") {
  const fs::path dir = fs::temp_directory_path() / ("sdb_gate_" + name);
  const auto r = run_cli("bench " + kRuns + " --out " + dir.string() + " " + kFlags, env);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return (dir / "results.json").string();
}

}  // namespace

TEST(Gate, PassesTwiceInARowAndFailsOnAPlantedSlowdown) {
  const std::string base = bench_into("base"), again1 = bench_into("again1"), again2 = bench_into("again2");
  const std::string slow = bench_into("slow", "SUBDIVBENCH_PLANT_SLOWDOWN=embree-subdiv");
  for (const auto& current : {again1, again2}) {
    const auto r = run_cli("gate --config " + test_config() + " --baseline " + base + " --current " + current);
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_EQ(r.out.find("REGRESSION"), std::string::npos) << r.out;
  }
  const auto r = run_cli("gate --config " + test_config() + " --baseline " + base + " --current " + slow);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("embree-subdiv/cpu/frog-standin/9"), std::string::npos);
  // Only the slowed scheme moved: its line says REGRESSION, the peer's does not.
  const size_t line = r.out.find("embree-subdiv/cpu/frog-standin/9");
  EXPECT_NE(r.out.substr(line, r.out.find('\n', line) - line).find("REGRESSION"), std::string::npos) << r.out;
  const size_t peer = r.out.find("osd-uniform/cpu/frog-standin/3");
  EXPECT_EQ(r.out.substr(peer, r.out.find('\n', peer) - peer).find("REGRESSION"), std::string::npos) << r.out;
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
  ASSERT_EQ(run_cli("gate --callgrind --record --baseline " + counts.string()).exit_code, 0);
  const auto same = run_cli("gate --callgrind --baseline " + counts.string());
  EXPECT_EQ(same.exit_code, 0) << same.out << same.err;
  EXPECT_NE(same.out.find("+0.00%"), std::string::npos) << same.out;
  const auto slow = run_cli("gate --callgrind --baseline " + counts.string(), "SUBDIVBENCH_PLANT_SLOWDOWN=osd-bfr");
  EXPECT_EQ(slow.exit_code, 1) << slow.out;
}
