// The closing summary of `run`: counts by status, every cracked row named, the files named.
#include <gtest/gtest.h>

#include <algorithm>

#include "harness/run/run_summary.h"

using namespace sdb;

namespace {

RunRow row(const std::string& mesh, RunStatus status, long open_edges, long cracks) {
  RunRow r;
  r.scheme = r.spec = "c-patch";
  r.mesh = mesh;
  r.level = 4;
  r.status = status;
  r.watertight.open_edges = open_edges;
  r.watertight.ray_cracks = cracks;
  r.watertight.rays = 100;
  return r;
}

}  // namespace

TEST(RunSummary, CountsStatusesAndNamesCrackedRows) {
  std::vector<RunRow> rows = {row("cube", RunStatus::Ok, 0, 0), row("torus", RunStatus::Failed, 2, 5),
                              row("open-patch", RunStatus::Ok, 32, -1),  // an open input's boundary
                              row("pole3", RunStatus::Unsupported, -1, -1), row("pole4", RunStatus::Failed, 0, 0)};
  rows[4].message = "deviation past the bound";
  const RunSummary s = summarise(rows);
  EXPECT_EQ(s.ok, 2u);
  EXPECT_EQ(s.unsupported, 1u);
  EXPECT_EQ(s.failed, 2u);
  ASSERT_EQ(s.not_watertight.size(), 1u);
  EXPECT_EQ(s.not_watertight[0], "c-patch/cpu/torus/4: 2 open edges, 5 ray cracks of 100 rays");
  ASSERT_EQ(s.failures.size(), 1u);
  EXPECT_EQ(s.failures[0], "c-patch/cpu/pole4/4: deviation past the bound");

  const auto lines = summary_lines(s, "out/results.json", "out");
  EXPECT_EQ(lines.front(), "5 rows: 2 ok, 1 unsupported, 2 failed");
  EXPECT_NE(std::find(lines.begin(), lines.end(), "  c-patch/cpu/torus/4: 2 open edges, 5 ray cracks of 100 rays"), lines.end());
  EXPECT_NE(std::find(lines.begin(), lines.end(), "wrote out/results.json"), lines.end());
  EXPECT_NE(std::find(lines.begin(), lines.end(), "wrote out/report.html (and out/report.md)"), lines.end());
}

TEST(RunSummary, SaysWhenEverythingIsWatertightAndNoReportWasWritten) {
  const auto lines = summary_lines(summarise({row("cube", RunStatus::Ok, 0, 0)}), "r.json", "");
  EXPECT_EQ(lines[1], "watertight: every closed input gave a closed surface without ray cracks");
  EXPECT_EQ(lines.back(), "wrote r.json");
}

TEST(PairedLines, ABackendCellHasItsOwnLineAndIsNoSchemesPeerRatio) {
  PairedCell peer_cell;
  peer_cell.mesh = "cube";
  peer_cell.row = {"cpatch", Backend::Vulkan, 17, 1000};
  peer_cell.peer = {"osd-bfr", Backend::CpuMt, 17, 1000};
  peer_cell.rounds = 3;
  peer_cell.rate_ratio_median = 0.5, peer_cell.rate_ratio_min = 0.4, peer_cell.rate_ratio_max = 0.6;
  peer_cell.time_ms_median = 2.0, peer_cell.peer_time_ms_median = 1.0;
  PairedCell backend_cell = peer_cell;
  backend_cell.peer = {"cpatch", Backend::CpuMt, 17, 1000};
  backend_cell.rate_ratio_median = 0.25, backend_cell.rate_ratio_min = 0.2, backend_cell.rate_ratio_max = 0.3;
  backend_cell.peer_time_ms_median = 0.5;
  const std::vector<std::string> lines = paired_lines({peer_cell, backend_cell});
  auto has = [&](const std::string& text) {
    return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(text) != std::string::npos; });
  };
  EXPECT_TRUE(has("0.50x osd-bfr/cpu-mt")) << "the vulkan row's ratio is to its peer";
  EXPECT_TRUE(has("GPU against the same scheme's CPU"));
  EXPECT_TRUE(has("0.250x cpu-mt (0.200-0.300 over 3 rounds; 2.000 against 0.500 ms)"));
  EXPECT_FALSE(has("0.25x cpatch/cpu-mt")) << "a backend cell read as a peer ratio";
}

TEST(PairedLines, RowsOnACpuImplementationOfVulkanAreMarkedAndSaidToBeNoGpu) {
  PairedCell cell;
  cell.mesh = "cube";
  cell.row = {"cpatch", Backend::Vulkan, 17, 1000};
  cell.peer = {"cpatch", Backend::CpuMt, 17, 1000};
  cell.rounds = 3;
  MachineInfo lavapipe;
  lavapipe.vulkan_device = "llvmpipe (LLVM 15.0.6, 256 bits)";
  lavapipe.vulkan_device_type = "cpu";
  const std::vector<std::string> lines = paired_lines({cell}, &lavapipe);
  auto has = [&](const std::string& text) {
    return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(text) != std::string::npos; });
  };
  EXPECT_TRUE(has(" vulkan* ")) << ::testing::PrintToString(lines);
  EXPECT_EQ(lines.back(), "* vulkan: llvmpipe (LLVM 15.0.6, 256 bits), a CPU implementation of Vulkan, not a GPU: its rates "
                          "check the device path, they are not GPU figures");
  MachineInfo gpu = lavapipe;
  gpu.vulkan_device_type = "discrete";
  const std::vector<std::string> plain = paired_lines({cell}, &gpu);
  EXPECT_TRUE(std::none_of(plain.begin(), plain.end(), [](const std::string& l) { return l.find('*') != std::string::npos; }));
}
