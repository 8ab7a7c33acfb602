// Which rows a run's summary cells pair (paired.h), and the ratio a round gives; nothing timed.
#include <gtest/gtest.h>

#include "harness/bench/paired.h"

using namespace sdb;

namespace {

RunRow row(const std::string& scheme, Backend backend, const std::string& mesh, int level, long triangles,
           const std::string& peer = "", std::optional<Backend> peer_backend = std::nullopt) {
  RunRow r;
  r.scheme = r.spec = scheme;
  r.backend = backend;
  r.mesh = mesh;
  r.level = level;
  r.triangles = triangles;
  r.peer = peer;
  r.peer_backend = peer_backend;
  return r;
}

}  // namespace

TEST(ChoosePairedCells, TheRowNearestAMillionAgainstThePeerNearestInTriangles) {
  const std::vector<RunRow> rows = {
      row("osd-bfr", Backend::Cpu, "cube", 9, 100'000), row("osd-bfr", Backend::Cpu, "cube", 33, 1'500'000),
      row("cpatch", Backend::Cpu, "cube", 9, 200'000, "osd-bfr", Backend::Cpu),
      row("cpatch", Backend::Cpu, "cube", 17, 800'000, "osd-bfr", Backend::Cpu),
      row("cpatch", Backend::Vulkan, "cube", 17, 800'000, "osd-bfr", Backend::CpuMt),  // no cpu-mt peer row
      row("cpatch", Backend::Cpu, "torus", 17, 800'000, "osd-bfr", Backend::Cpu),    // no peer row on torus
  };
  const std::vector<PairedPlanCell> cells = choose_paired_cells(rows);
  ASSERT_EQ(cells.size(), 1u);
  EXPECT_EQ(cells[0].row.level, 17);   // 800 k is nearer 1 M than 200 k
  EXPECT_EQ(cells[0].peer.level, 33);  // 1.5 M is nearer 800 k (in ratio) than 100 k
}

TEST(ChoosePairedCells, RowsThatAreNotOkAreNeitherSide) {
  std::vector<RunRow> rows = {row("osd-bfr", Backend::Cpu, "cube", 9, 100'000),
                              row("cpatch", Backend::Cpu, "cube", 9, 100'000, "osd-bfr", Backend::Cpu)};
  rows[0].status = RunStatus::Failed;
  EXPECT_TRUE(choose_paired_cells(rows).empty());
  rows[0].status = RunStatus::Ok;
  rows[1].status = RunStatus::Unsupported;
  EXPECT_TRUE(choose_paired_cells(rows).empty());
}

TEST(PairRounds, RatioOfRatesPerRoundWithMedianAndRange) {
  RunRow scheme = row("cpatch", Backend::Cpu, "cube", 17, 2000);
  RunRow peer = row("osd-bfr", Backend::Cpu, "cube", 33, 1000);
  scheme.time_ms.samples = {1.0, 2.0, 4.0};
  peer.time_ms.samples = {2.0, 2.0, 2.0};
  const PairedCell c = pair_rounds("cube", scheme, peer);
  EXPECT_EQ(c.rounds, 3);
  // Round r: (2000 / t_r) / (1000 / 2) = 4 / t_r.
  EXPECT_EQ(c.rate_ratio_per_round, (std::vector<double>{4.0, 2.0, 1.0}));
  EXPECT_DOUBLE_EQ(c.rate_ratio_median, 2.0);
  EXPECT_DOUBLE_EQ(c.rate_ratio_min, 1.0);
  EXPECT_DOUBLE_EQ(c.rate_ratio_max, 4.0);
  EXPECT_DOUBLE_EQ(c.time_ms_median, 2.0);
  EXPECT_DOUBLE_EQ(c.peer_time_ms_median, 2.0);
  EXPECT_EQ(c.row.scheme, "cpatch");
  EXPECT_EQ(c.peer.level, 33);
}

TEST(PairRounds, GpuRowsUseTheirGpuTime) {
  RunRow scheme = row("cpatch", Backend::Vulkan, "cube", 17, 1000);
  RunRow peer = row("osd-bfr", Backend::CpuMt, "cube", 17, 1000);
  scheme.time_ms.samples = {10.0, 10.0};          // wall time, readback included
  scheme.gpu_time_ms = TimeStats{1, 1, 1, 2, {1.0, 1.0}};
  peer.time_ms.samples = {2.0, 2.0};
  EXPECT_DOUBLE_EQ(pair_rounds("cube", scheme, peer).rate_ratio_median, 2.0);
}

TEST(ChoosePairedCells, AGpuRowIsAlsoPairedWithItsOwnSchemeOnTheCpuAtItsLevel) {
  const std::vector<RunRow> rows = {
      row("osd-bfr", Backend::CpuMt, "cube", 17, 800'000),
      row("cpatch", Backend::CpuMt, "cube", 9, 200'000, "osd-bfr", Backend::CpuMt),
      row("cpatch", Backend::CpuMt, "cube", 17, 800'000, "osd-bfr", Backend::CpuMt),
      row("cpatch", Backend::Vulkan, "cube", 17, 800'000, "osd-bfr", Backend::CpuMt),
      row("cpatch", Backend::Vulkan, "torus", 17, 800'000, "osd-bfr", Backend::CpuMt),  // no cpu-mt row on torus
      row("cpatch:n=3", Backend::Vulkan, "cube", 17, 800'000, "osd-bfr", Backend::CpuMt),  // another spec
  };
  const std::vector<PairedPlanCell> cells = choose_paired_cells(rows);
  // Peer cells first (cpatch cpu-mt, cpatch vulkan and cpatch:n=3 vulkan against osd-bfr), then the one backend cell.
  ASSERT_EQ(cells.size(), 4u);
  const PairedPlanCell& gpu = cells.back();
  EXPECT_EQ(gpu.row.backend, Backend::Vulkan);
  EXPECT_EQ(gpu.row.spec, "cpatch");
  EXPECT_EQ(gpu.peer.spec, "cpatch");
  EXPECT_EQ(gpu.peer.backend, Backend::CpuMt);
  EXPECT_EQ(gpu.peer.level, 17);  // the GPU row's level, not the one nearest in triangles
  for (size_t i = 0; i + 1 < cells.size(); ++i) EXPECT_EQ(cells[i].peer.scheme, "osd-bfr");
}

TEST(PairRounds, ABackendCellIsTheSameSchemeOnAnotherBackend) {
  RunRow gpu = row("cpatch", Backend::Vulkan, "cube", 17, 1000), cpu = row("cpatch", Backend::CpuMt, "cube", 17, 1000);
  gpu.gpu_time_ms = TimeStats{4, 4, 4, 1, {4.0}};
  cpu.time_ms.samples = {1.0};
  const PairedCell c = pair_rounds("cube", gpu, cpu);
  EXPECT_TRUE(is_backend_cell(c));
  EXPECT_DOUBLE_EQ(c.rate_ratio_median, 0.25);
  EXPECT_FALSE(is_backend_cell(pair_rounds("cube", gpu, row("osd-bfr", Backend::CpuMt, "cube", 17, 1000))));
}

TEST(PairMeasuredRows, RowsTimedInTheSameRoundsPairAsTheyAre) {
  std::vector<RunRow> rows = {
      row("osd-bfr", Backend::CpuMt, "cube", 17, 1000),
      row("cpatch", Backend::CpuMt, "cube", 17, 1000, "osd-bfr", Backend::CpuMt),
      row("cpatch", Backend::Vulkan, "cube", 17, 1000, "osd-bfr", Backend::CpuMt),
  };
  rows[0].time_ms.samples = {4.0, 4.0};
  rows[1].time_ms.samples = {1.0, 2.0};
  rows[2].time_ms.samples = {9.0, 9.0};  // wall time; the GPU's is what pairs
  rows[2].gpu_time_ms = TimeStats{4, 4, 4, 2, {4.0, 4.0}};
  const std::vector<PairedCell> cells = pair_measured_rows(rows);
  ASSERT_EQ(cells.size(), 3u);
  EXPECT_EQ(cells[0].rate_ratio_per_round, (std::vector<double>{4.0, 2.0}));  // cpatch cpu-mt / osd-bfr
  EXPECT_EQ(cells[1].rate_ratio_per_round, (std::vector<double>{1.0, 1.0}));  // cpatch vulkan / osd-bfr
  EXPECT_TRUE(is_backend_cell(cells[2]));
  EXPECT_EQ(cells[2].rate_ratio_per_round, (std::vector<double>{0.25, 0.5}));  // cpatch vulkan / its cpu-mt
}
