// How the gate judges a Vulkan row (gate.h): by its kernel timestamps, over its peer on the peer's
// backend in the same round, or (ci/gate.json's normalisers) over its own cpu-mt row; and what it
// enforces against a baseline from another machine. Nothing timed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <functional>

#include "harness/gate/gate.h"
#include "tests/timed_rows.h"

using namespace sdb;
namespace fs = std::filesystem;

namespace {

RunRow row(const std::string& scheme, Backend backend, std::vector<double> samples,
           std::optional<Backend> peer_backend = std::nullopt) {
  return test::timed_row(scheme, backend, std::move(samples), peer_backend ? "osd-bfr" : "", peer_backend);
}

// Nine rounds: the write probes and osd-bfr (the anchor, normalised by them) on cpu and cpu-mt,
// cpatch-2pass on cpu-mt (`cpu_mt`), and a Vulkan row whose wall and kernel times are given.
ResultsFile run(const std::vector<double>& vulkan_wall, const std::vector<double>& vulkan_kernel,
                const std::vector<double>& cpu_mt = std::vector<double>(9, 1.0)) {
  ResultsFile f;
  f.rounds = 9;
  f.runs.push_back(row(kCalibrationScheme, Backend::Cpu, std::vector<double>(9, 1.0)));
  f.runs.push_back(row(kCalibrationScheme, Backend::CpuMt, std::vector<double>(9, 1.0)));
  f.runs.push_back(row("osd-bfr", Backend::Cpu, std::vector<double>(9, 1.0)));
  f.runs.push_back(row("osd-bfr", Backend::CpuMt, std::vector<double>(9, 0.5)));
  f.runs.push_back(row("cpatch-2pass", Backend::CpuMt, cpu_mt, Backend::CpuMt));
  RunRow v = row("cpatch-2pass", Backend::Vulkan, vulkan_wall, Backend::CpuMt);
  v.gpu_time_ms = TimeStats{1, 1, 1, int(vulkan_kernel.size()), vulkan_kernel};
  f.runs.push_back(v);
  return f;
}

const GateEntry& vulkan_entry(const GateReport& r) {
  for (const GateEntry& e : r.entries)
    if (e.name.find("/vulkan/") != std::string::npos) return e;
  throw std::runtime_error("no vulkan entry");
}

std::vector<double> around(double t) {
  return {t, t * 1.01, t * 0.99, t * 1.02, t * 0.98, t * 1.03, t * 0.97, t * 1.01, t * 0.99};
}

}  // namespace

TEST(GateVulkanRows, KernelTwiceAsSlowIsARegressionAgainstTheCpuMtPeer) {
  GateConfig config;
  config.thresholds = {{"/vulkan/", 0.40}};
  const GateReport r = run_gate(run(around(5.0), around(2.0)), run(around(5.0), around(4.0)), config);
  const GateEntry& e = vulkan_entry(r);
  EXPECT_EQ(e.normaliser, "osd-bfr, paired");
  EXPECT_NEAR(e.change, 1.0, 0.05);
  EXPECT_DOUBLE_EQ(e.threshold, 0.40);
  EXPECT_TRUE(e.regression);
  EXPECT_TRUE(r.failed());
}

TEST(GateVulkanRows, WallTimeAloneDoesNotMoveTheVerdict) {
  GateConfig config;
  const GateReport r = run_gate(run(around(5.0), around(2.0)), run(around(10.0), around(2.0)), config);
  EXPECT_FALSE(vulkan_entry(r).regression);
  EXPECT_FALSE(r.failed());
}

TEST(GateVulkanRows, ANormaliserNamesTheRowsOwnCpuMtRun) {
  GateConfig config;
  config.thresholds = {{"/vulkan/", 0.40}};
  config.normalisers = {{"/vulkan/", Backend::CpuMt}};
  // The machine got busier for both of the scheme's rows (kernel and cpu-mt twice as slow): no change.
  const GateReport same = run_gate(run(around(5.0), around(2.0), around(1.0)), run(around(5.0), around(4.0), around(2.0)), config);
  EXPECT_EQ(vulkan_entry(same).normaliser, "cpatch-2pass/cpu-mt, paired");
  EXPECT_NEAR(vulkan_entry(same).change, 0.0, 0.05);
  EXPECT_FALSE(vulkan_entry(same).regression);
  // Only the kernel slowed down: a regression.
  const GateReport slow = run_gate(run(around(5.0), around(2.0), around(1.0)), run(around(5.0), around(4.0), around(1.0)), config);
  EXPECT_TRUE(vulkan_entry(slow).regression);
  // Without its cpu-mt row the Vulkan row cannot be judged, and says so.
  ResultsFile missing = run(around(5.0), around(2.0));
  missing.runs.erase(missing.runs.begin() + 4);
  const GateReport none = run_gate(run(around(5.0), around(2.0)), missing, config);
  ASSERT_EQ(none.problems.size(), 1u);
  EXPECT_NE(none.problems[0].find("its own row on cpu-mt"), std::string::npos) << none.problems[0];
}

// A baseline from another processor: the ratios between kernels move with it, so a slowdown is
// shown, not enforced; the same slowdown on the same processor fails.
TEST(GateMachines, ABaselineFromAnotherProcessorIsShownNotEnforced) {
  GateConfig config;
  config.thresholds = {{"/vulkan/", 0.40}};
  ResultsFile baseline = run(around(5.0), around(2.0)), current = run(around(5.0), around(4.0));
  baseline.machine.cpu_model = "AMD EPYC";
  current.machine.cpu_model = "Intel(R) Xeon(R) Processor";
  baseline.machine.cores = current.machine.cores = 2;
  const GateReport other = run_gate(baseline, current, config);
  EXPECT_TRUE(vulkan_entry(other).regression);
  EXPECT_NE(other.other_machine.find("AMD EPYC"), std::string::npos);
  EXPECT_FALSE(other.failed());

  current.machine.cpu_model = "AMD EPYC";
  current.machine.cores = 4;
  EXPECT_FALSE(run_gate(baseline, current, config).failed()) << "another core count is another machine";

  current.machine.cores = 2;
  const GateReport same = run_gate(baseline, current, config);
  EXPECT_TRUE(same.other_machine.empty());
  EXPECT_TRUE(same.failed());
}

// ci/baselines/: the baseline recorded on this processor and core count is found among others by
// what its file says, not by its name; none matching leaves the default (CI's) in place.
TEST(GateMachines, APerMachineBaselineIsFoundByItsProcessorAndCores) {
  MachineInfo xeon;
  xeon.cpu_model = "Intel(R) Xeon(R) Processor";
  xeon.cores = 2;
  EXPECT_EQ(machine_baseline_name(xeon), "intel-r-xeon-r-processor-2c.json");

  const fs::path dir = fs::temp_directory_path() / ("sdb_machine_baselines_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const auto recorded_on = [&](const std::string& file, const std::string& model, int cores) {
    ResultsFile r = run(around(5.0), around(2.0));
    r.machine.cpu_model = model;
    r.machine.cores = cores;
    write_results(r, (dir / file).string());
    return (dir / file).string();
  };
  const std::string epyc = recorded_on("a.json", "AMD EPYC", 2), xeon4 = recorded_on("b.json", xeon.cpu_model, 4),
                    own = recorded_on("c.json", xeon.cpu_model, 2);
  EXPECT_EQ(baseline_for_machine(xeon, {epyc, xeon4, own}), own);
  EXPECT_EQ(baseline_for_machine(xeon, {epyc, xeon4}), std::nullopt);
  MachineInfo unnamed;
  EXPECT_EQ(baseline_for_machine(unnamed, {epyc, own}), std::nullopt) << "a run naming no processor matches none";
  fs::remove_all(dir);
}

// Every baseline benchmark must have an ok row in the current file: one that crashed, became
// unsupported, was dropped or renamed fails the gate, named, on any machine; a renamed one's new
// name is reported as new.
TEST(GateGaps, ABaselineBenchmarkWithoutAnOkCurrentRowFailsTheGateNamingIt) {
  const ResultsFile baseline = run(around(5.0), around(2.0));
  const std::string vulkan = "cpatch-2pass/vulkan/cube/9";
  EXPECT_TRUE(run_gate(baseline, baseline, GateConfig{}).gaps.empty());
  EXPECT_FALSE(run_gate(baseline, baseline, GateConfig{}).failed());
  struct Case {
    std::string name, why;
    std::function<void(std::vector<RunRow>&)> change;
  };
  const std::vector<Case> cases = {
      {"crashed", "failed: crashed during execute: killed by signal 11",
       [](std::vector<RunRow>& rows) {
         rows.back().status = RunStatus::Failed;
         rows.back().message = "crashed during execute: killed by signal 11";
       }},
      {"unsupported", "unsupported: no Vulkan device",
       [](std::vector<RunRow>& rows) {
         rows.back().status = RunStatus::Unsupported;
         rows.back().message = "no Vulkan device";
       }},
      {"dropped", "missing from the current file (dropped or renamed)", [](std::vector<RunRow>& rows) { rows.pop_back(); }},
      {"renamed", "missing from the current file (dropped or renamed)",
       [](std::vector<RunRow>& rows) { rows.back().spec = "cpatch-2pass:n=2"; }},
  };
  for (const Case& c : cases) {
    ResultsFile current = run(around(5.0), around(2.0));
    c.change(current.runs);
    current.machine.cpu_model = "another processor";  // timing verdicts advisory; a missing benchmark is not
    ResultsFile base = baseline;
    base.machine.cpu_model = "the baseline's processor";
    const GateReport r = run_gate(base, current, GateConfig{});
    ASSERT_EQ(r.gaps.size(), 1u) << c.name;
    EXPECT_EQ(r.gaps[0].name, vulkan) << c.name;
    EXPECT_EQ(r.gaps[0].why, c.why) << c.name;
    EXPECT_FALSE(r.other_machine.empty());
    EXPECT_TRUE(r.failed()) << c.name << ": the gate passed a benchmark that stopped running";
    if (c.name == "renamed") EXPECT_EQ(r.new_rows, std::vector<std::string>{"cpatch-2pass:n=2/vulkan/cube/9"});
    else EXPECT_TRUE(r.new_rows.empty()) << c.name;
  }
}
