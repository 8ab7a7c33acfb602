// The report's first screen as computed in C++ (overview.h): the summary cells as points, the
// Pareto front, exact rows at the precision floor, lavapipe never ranked as a GPU, the paired
// ratio with its range and watertightness over closed inputs.
#include "reports/overview.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>

using namespace sdb;

namespace {

RunRow row(const std::string& scheme, Backend b, const std::string& mesh, int level, long triangles, double rate,
           const std::string& limit, double p95) {
  RunRow r;
  r.scheme = r.spec = scheme;
  r.role = "method";
  r.backend = b;
  r.mesh = mesh;
  r.level = level;
  r.triangles = triangles;
  r.triangle_rate_mtris = rate;
  r.limit = limit;
  r.deviation.measured = true;
  r.deviation.pos_p95_rel_diag = p95;
  r.watertight = {0, 1000, 0};
  return r;
}

const OverviewPoint* point(const BackendOverview& b, const std::string& scheme, const std::string& mesh) {
  for (const auto& p : b.points)
    if (p.scheme == scheme && p.mesh == mesh) return &p;
  return nullptr;
}

ResultsFile sample() {
  ResultsFile f;
  f.machine.vulkan_device = "llvmpipe (LLVM 15.0.6, 256 bits)";
  f.machine.vulkan_device_type = "cpu";
  f.runs = {
      // exact and fast: on the front at the floor; its 100 k row is not the summary cell
      row("fast-exact", Backend::Cpu, "ball", 4, 100'000, 900, "reproduces", 3e-7),  // its peer: slow-exact
      row("fast-exact", Backend::Cpu, "ball", 5, 1'000'000, 500, "reproduces", 3e-7),
      // slower and exact: dominated by fast-exact
      row("slow-exact", Backend::Cpu, "ball", 5, 1'000'000, 100, "reproduces", 2e-7),
      // faster still but approximate: on the front above the floor
      row("approx", Backend::Cpu, "ball", 17, 1'200'000, 2000, "approximates", 4e-4),
      // approximate and slower than fast-exact: dominated
      row("approx-slow", Backend::Cpu, "ball", 17, 1'200'000, 50, "approximates", 1e-3),
      // too small for the summary: listed, not drawn
      row("tiny", Backend::Cpu, "ball", 9, 12'000, 5000, "reproduces", 1e-7),
      // lavapipe: drawn in its own figure, its best rate never the scheme's best where a CPU row exists
      row("fast-exact", Backend::Vulkan, "ball", 5, 1'000'000, 9000, "reproduces", 3e-7),
  };
  for (RunRow& r : f.runs)
    if (r.scheme == "fast-exact") r.peer = "slow-exact";
  RunRow leaky = row("approx", Backend::Cpu, "cube", 17, 1'000'000, 1500, "approximates", 2e-4);
  leaky.watertight.ray_cracks = 3;
  f.runs.push_back(leaky);
  PairedCell c;
  c.mesh = "ball";
  c.row = {"fast-exact", Backend::Cpu, 5, 1'000'000};
  c.peer = {"slow-exact", Backend::Cpu, 5, 1'000'000};
  c.rounds = 3;
  c.rate_ratio_per_round = {4.5, 5.0, 5.5};
  c.rate_ratio_median = 5.0, c.rate_ratio_min = 4.5, c.rate_ratio_max = 5.5;
  c.time_ms_median = 2.0;  // 1 M triangles in 2 ms: the paired rate, 500 M/s
  f.paired.push_back(c);
  return f;
}

}  // namespace

TEST(Overview, ParetoFrontExactAtTheFloorAndCellsOutsideTheBandNotDrawn) {
  const ReportOverview o = make_overview(sample());
  ASSERT_EQ(o.backends.size(), 2u);
  const BackendOverview& cpu = o.backends[0];
  EXPECT_EQ(cpu.backend, Backend::Cpu);
  EXPECT_TRUE(cpu.cpu_implementation.empty());
  const OverviewPoint* fast = point(cpu, "fast-exact", "ball");
  ASSERT_NE(fast, nullptr);
  EXPECT_EQ(fast->triangles, 1'000'000) << "the summary cell is the paired row, not the 100 k one";
  EXPECT_TRUE(fast->paired);
  EXPECT_DOUBLE_EQ(fast->rate_mtris, 500);
  EXPECT_TRUE(fast->exact);
  EXPECT_DOUBLE_EQ(fast->plotted_p95, kPrecisionFloorRelDiag);
  EXPECT_TRUE(fast->pareto);
  EXPECT_FALSE(point(cpu, "slow-exact", "ball")->pareto);
  EXPECT_TRUE(point(cpu, "approx", "ball")->pareto);
  EXPECT_DOUBLE_EQ(point(cpu, "approx", "ball")->plotted_p95, 4e-4);
  EXPECT_FALSE(point(cpu, "approx-slow", "ball")->pareto);
  EXPECT_EQ(point(cpu, "tiny", "ball"), nullptr);
  ASSERT_EQ(cpu.unplotted.size(), 1u);
  EXPECT_NE(cpu.unplotted[0].find("tiny on ball: 12000 triangles"), std::string::npos) << cpu.unplotted[0];
  const BackendOverview& vulkan = o.backends[1];
  EXPECT_NE(vulkan.cpu_implementation.find("a CPU implementation of Vulkan, not a GPU"), std::string::npos);
}

TEST(Overview, PerSchemeRowsRankNoCpuImplementationAndCountClosedInputs) {
  const ReportOverview o = make_overview(sample());
  std::map<std::string, SchemeOverview> by;
  for (const auto& s : o.schemes) by[s.scheme] = s;
  const SchemeOverview& fast = by.at("fast-exact");
  EXPECT_DOUBLE_EQ(fast.best_rate_mtris, 500) << "lavapipe's 9000 is not the scheme's best rate";
  EXPECT_EQ(fast.best_backend, Backend::Cpu);
  EXPECT_FALSE(fast.best_on_cpu_implementation);
  EXPECT_EQ(fast.limit, "exact");
  EXPECT_EQ(fast.peer, "slow-exact");
  EXPECT_EQ(fast.paired_cells, 1);
  EXPECT_DOUBLE_EQ(fast.ratio_median, 5.0);
  EXPECT_DOUBLE_EQ(fast.ratio_min, 4.5);
  EXPECT_DOUBLE_EQ(fast.ratio_max, 5.5);
  EXPECT_EQ(fast.closed_inputs, 1);
  EXPECT_EQ(fast.watertight_inputs, 1);
  const SchemeOverview& approx = by.at("approx");
  EXPECT_EQ(approx.limit, "approximates");
  EXPECT_DOUBLE_EQ(approx.worst_p95_rel_diag, 4e-4);
  EXPECT_EQ(approx.closed_inputs, 2);
  EXPECT_EQ(approx.watertight_inputs, 1) << "the cube's cracked row";
  EXPECT_EQ(by.at("tiny").best_in_band, false);
  EXPECT_EQ(by.at("slow-exact").peer, "") << "the anchor";
  EXPECT_EQ(by.at("slow-exact").paired_cells, 0);
  const auto j = overview_json(o);
  EXPECT_EQ(j["backends"][0]["backend"], "cpu");
  EXPECT_EQ(j["schemes"].size(), o.schemes.size());
}

// The single-pass ratio, once, in C++ (the report's row table and its unpaired summary cells read
// it): the row's rate over its peer's ok row on the peer backend at the same mesh and tessellation.
TEST(Overview, SinglePassRatioIsTheRowsRateOverItsPeersRowOfTheSameTessellation) {
  ResultsFile f;
  auto at = [](RunRow r, int tessellation, const std::string& peer, std::optional<Backend> peer_backend) {
    r.tessellation = tessellation, r.peer = peer, r.peer_backend = peer_backend;
    return r;
  };
  f.runs = {
      at(row("peer", Backend::Cpu, "ball", 3, 1'000'000, 100, "reproduces", 1e-7), 8, "", std::nullopt),
      at(row("peer", Backend::Cpu, "ball", 4, 4'000'000, 0, "reproduces", 1e-7), 16, "", std::nullopt),
      at(row("mine", Backend::Cpu, "ball", 3, 1'000'000, 300, "reproduces", 1e-7), 8, "peer", Backend::Cpu),
      at(row("mine", Backend::Vulkan, "ball", 3, 1'000'000, 50, "reproduces", 1e-7), 8, "peer", Backend::Cpu),
      at(row("mine", Backend::Cpu, "ball", 4, 4'000'000, 300, "reproduces", 1e-7), 16, "peer", Backend::Cpu),
      at(row("mine", Backend::CpuMt, "ball", 3, 1'000'000, 900, "reproduces", 1e-7), 8, "peer", Backend::CpuMt),
      at(row("mine", Backend::Cpu, "cube", 3, 1'000'000, 300, "reproduces", 1e-7), 8, "peer", Backend::Cpu),
  };
  f.runs.back().status = RunStatus::Failed;
  const ReportOverview o = make_overview(f);
  ASSERT_EQ(o.row_peer_ratios.size(), f.runs.size());
  EXPECT_TRUE(std::isnan(o.row_peer_ratios[0])) << "the anchor has no peer";
  EXPECT_DOUBLE_EQ(o.row_peer_ratios[2], 3.0);
  EXPECT_DOUBLE_EQ(o.row_peer_ratios[3], 0.5) << "a Vulkan row against its peer's cpu row";
  EXPECT_TRUE(std::isnan(o.row_peer_ratios[4])) << "a peer row without a rate";
  EXPECT_TRUE(std::isnan(o.row_peer_ratios[5])) << "no peer row on cpu-mt";
  EXPECT_TRUE(std::isnan(o.row_peer_ratios[6])) << "a failed row";
  std::map<std::string, SummaryCellRef> cells;
  for (const auto& c : o.cells) cells[c.scheme + "/" + std::string(to_string(c.backend)) + "/" + c.mesh] = c;
  EXPECT_DOUBLE_EQ(cells.at("mine/cpu/ball").ratio, 3.0) << "the summary cell nearest 1 M triangles, single pass";
  EXPECT_DOUBLE_EQ(cells.at("mine/vulkan/ball").ratio, 0.5);
  EXPECT_TRUE(std::isnan(cells.at("mine/cpu/cube").ratio));
  const auto j = overview_json(o);
  EXPECT_EQ(j["row_peer_ratios"][2], 3.0);
  EXPECT_TRUE(j["row_peer_ratios"][0].is_null());
  // A paired cell's ratio is its rounds' median, not the single pass.
  ResultsFile paired = sample();
  for (const auto& c : make_overview(paired).cells)
    if (c.scheme == "fast-exact" && c.mesh == "ball" && c.backend == Backend::Cpu) EXPECT_DOUBLE_EQ(c.ratio, 5.0);
}

// The limit table: per scheme and mesh, "reproduces" unless a row approximates, then the worst max
// and p95 over the approximating rows and their levels; rows without a claim or a deviation, and
// unsupported rows, say nothing.
TEST(Overview, LimitTableTakesTheWorstOfTheApproximatingRows) {
  ResultsFile f;
  RunRow coarse = row("approx", Backend::Cpu, "ball", 2, 10'000, 10, "approximates", 4e-4);
  coarse.deviation.pos_max_rel_diag = 1e-3;
  RunRow fine = row("approx", Backend::Cpu, "ball", 3, 40'000, 10, "approximates", 3e-4);
  fine.deviation.pos_max_rel_diag = 2e-3;
  fine.deviation.measured_by = "nearest-point";
  RunRow refused = row("approx", Backend::Cpu, "ball", 4, 160'000, 10, "approximates", 9e-1);
  refused.status = RunStatus::Unsupported;
  RunRow unmeasured = row("approx", Backend::Vulkan, "ball", 4, 160'000, 10, "approximates", 9e-1);
  unmeasured.deviation = DeviationFigures{};
  RunRow unclaimed = row("older", Backend::Cpu, "ball", 1, 10'000, 10, "", 1e-7);
  f.runs = {row("approx", Backend::Cpu, "ball", 1, 2'500, 10, "reproduces", 1e-7), coarse, fine, refused, unmeasured,
            row("exact", Backend::Cpu, "cube", 1, 2'500, 10, "reproduces", 1e-7), unclaimed,
            row("approx", Backend::Cpu, "cube", 2, 10'000, 10, "approximates", 5e-4)};
  f.runs.back().deviation.pos_max_rel_diag = NAN;  // null in the file: not measured
  const ReportOverview o = make_overview(f);
  ASSERT_EQ(o.limits.size(), 3u) << "approx on ball and cube, exact on cube; nothing of the unclaimed row";
  const LimitCell& ball = o.limits[0];
  EXPECT_EQ(ball.scheme, "approx");
  EXPECT_EQ(ball.mesh, "ball");
  EXPECT_TRUE(ball.approximates);
  EXPECT_DOUBLE_EQ(ball.worst_max_rel_diag, 2e-3);
  EXPECT_DOUBLE_EQ(ball.worst_p95_rel_diag, 4e-4) << "the unsupported row's 0.9 is not a figure";
  EXPECT_EQ(ball.approximating_levels, (std::vector<int>{2, 3}));
  EXPECT_TRUE(ball.some_reproduce);
  EXPECT_TRUE(ball.nearest_point);
  EXPECT_EQ(o.limits[1].scheme, "exact");
  EXPECT_FALSE(o.limits[1].approximates);
  EXPECT_EQ(o.limits[2].mesh, "cube");
  EXPECT_FALSE(o.limits[2].some_reproduce);
  EXPECT_TRUE(std::isnan(o.limits[2].worst_max_rel_diag)) << "p95 measured, max not: " << o.limits[2].worst_max_rel_diag;
  const auto j = overview_json(o);
  EXPECT_EQ(j["limits"][0]["limit"], "approximates");
  EXPECT_EQ(j["limits"][1]["limit"], "reproduces");
  EXPECT_TRUE(j["limits"][2]["worst_max_rel_diag"].is_null());
}
