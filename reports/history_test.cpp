// The history's figures and verdicts (history.h) are the gate's: run_gate on each pair of files,
// Vulkan rows included (over their own cpu-mt row where the config says so), a gap where a row
// is gone. Nothing timed.
#include "reports/history.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "tests/timed_rows.h"

using namespace sdb;
namespace fs = std::filesystem;

namespace {

RunRow row(const std::string& scheme, Backend backend, std::vector<double> samples, const std::string& peer = "",
           std::optional<Backend> peer_backend = std::nullopt) {
  return test::timed_row(scheme, backend, std::move(samples), peer, peer_backend, 3);
}

std::vector<double> around(double t) {
  return {t, t * 1.01, t * 0.99, t * 1.02, t * 0.98, t * 1.03, t * 0.97, t * 1.01, t * 0.99};
}

// Nine rounds: the write probe, osd-bfr, fragments-cc on cpu-mt and on vulkan (kernel times given).
ResultsFile commit(const std::string& sha, double vulkan_kernel, bool with_vulkan = true) {
  ResultsFile f;
  f.rounds = 9;
  f.machine.git_commit = sha;
  f.runs.push_back(row(kCalibrationScheme, Backend::Cpu, around(1.0)));
  f.runs.push_back(row(kCalibrationScheme, Backend::CpuMt, around(1.0)));
  f.runs.push_back(row("osd-bfr", Backend::CpuMt, around(2.0)));
  f.runs.push_back(row("fragments-cc", Backend::CpuMt, around(1.0), "osd-bfr", Backend::CpuMt));
  if (with_vulkan) {
    RunRow v = row("fragments-cc", Backend::Vulkan, around(9.0), "osd-bfr", Backend::CpuMt);
    v.gpu_time_ms = TimeStats{1, 1, 1, 9, around(vulkan_kernel)};
    f.runs.push_back(v);
  }
  return f;
}

GateConfig vulkan_over_cpu_mt() {
  GateConfig c;
  c.normalisers = {{"/vulkan/", Backend::CpuMt}};
  return c;
}

const HistoryBenchmark& find(const History& h, const std::string& name) {
  for (const auto& b : h.benchmarks)
    if (b.name == name) return b;
  throw std::runtime_error("no benchmark " + name);
}

// Every step of the history is the gate's entry, gap or problem for the same pair of files.
void expect_gate_verdicts(const std::vector<ResultsFile>& files, const GateConfig& config) {
  const History h = make_history(files, config);
  int judged = 0;
  for (size_t i = 1; i < files.size(); ++i) {
    const GateReport g = run_gate(files[i - 1], files[i], config);
    for (const GateEntry& e : g.entries) {
      const auto& step = find(h, e.name).steps[i];
      ASSERT_TRUE(step) << e.name;
      EXPECT_EQ(step->verdict, e.regression ? "slower" : e.improvement ? "faster" : "same") << e.name;
      EXPECT_DOUBLE_EQ(step->change, e.change) << e.name;
      EXPECT_DOUBLE_EQ(step->p_value, e.p_value) << e.name;
      ++judged;
    }
    for (const GateGap& gap : g.gaps) EXPECT_EQ(find(h, gap.name).steps[i]->verdict, "gap") << gap.name;
  }
  std::printf("history: %d steps judged, each equal to the gate's entry\n", judged);
  EXPECT_GT(judged, 0);
}

}  // namespace

TEST(History, APlantedVulkanRegressionIsSlowerAsTheGateSays) {
  const std::vector<ResultsFile> files = {commit("aaaaaaaaaaaaaaaa", 2.0), commit("bbbbbbbbbbbbbbbb", 4.0)};
  const History h = make_history(files, vulkan_over_cpu_mt());
  const HistoryBenchmark& v = h.benchmarks.front();  // the one the gate calls slower comes first
  EXPECT_EQ(v.name, "fragments-cc/vulkan/cube/3");
  EXPECT_EQ(v.normaliser, "fragments-cc/cpu-mt, paired");
  ASSERT_TRUE(v.steps[1]);
  EXPECT_EQ(v.steps[1]->verdict, "slower");
  EXPECT_NEAR(v.steps[1]->change, 1.0, 0.05);
  ASSERT_TRUE(v.spans[0] && v.spans[1]);
  EXPECT_NEAR(v.spans[1]->median / v.spans[0]->median, 2.0, 0.05);
  EXPECT_FALSE(v.steps[0]);
  EXPECT_EQ(find(h, "fragments-cc/cpu-mt/cube/3").steps[1]->verdict, "same");
  EXPECT_EQ(h.labels, (std::vector<std::string>{"aaaaaaaaaaaa", "bbbbbbbbbbbb"}));
  expect_gate_verdicts(files, vulkan_over_cpu_mt());
}

TEST(History, AVulkanRowGoneIsTheGatesGap) {
  const std::vector<ResultsFile> files = {commit("a", 2.0), commit("a", 2.0, false)};
  const History h = make_history(files, vulkan_over_cpu_mt());
  EXPECT_EQ(h.labels, (std::vector<std::string>{"a", "a #2"}));
  const HistoryBenchmark& v = h.benchmarks.front();
  EXPECT_EQ(v.name, "fragments-cc/vulkan/cube/3");
  ASSERT_TRUE(v.steps[1]);
  EXPECT_EQ(v.steps[1]->verdict, "gap");
  EXPECT_FALSE(v.spans[1]);
  expect_gate_verdicts(files, vulkan_over_cpu_mt());
}

TEST(History, TooFewRepetitionsAreNotJudgedAsTheGateSays) {
  GateConfig config = vulkan_over_cpu_mt();
  config.min_repetitions = 10;
  const History h = make_history({commit("a", 2.0), commit("b", 4.0)}, config);
  const auto& step = find(h, "fragments-cc/vulkan/cube/3").steps[1];
  ASSERT_TRUE(step);
  EXPECT_EQ(step->verdict, "not judged");
  EXPECT_NE(step->why.find("repetitions"), std::string::npos) << step->why;
}

TEST(History, TheFixturesHistoryIsTheGatesOnEveryPair) {
  const fs::path dir = fs::path(SDB_SOURCE_DIR) / "reports" / "testdata" / "history";
  std::vector<ResultsFile> files;
  for (const char* f : {"a.json", "b.json", "c.json"}) files.push_back(read_results((dir / f).string()));
  const GateConfig config = read_gate_config((fs::path(SDB_SOURCE_DIR) / "ci" / "gate.json").string());
  const History h = make_history(files, config);
  // c.json's planted slowdown: cpatch-2pass on frog-standin, 1.6 times, round by round.
  EXPECT_EQ(h.benchmarks.front().name, "cpatch-2pass/cpu/frog-standin/9");
  EXPECT_EQ(h.benchmarks.front().steps[2]->verdict, "slower");
  expect_gate_verdicts(files, config);
}
