#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "harness/bench/machine.h"
#include "harness/bench/measure.h"
#include "harness/core/errors.h"
#include "harness/results/results.h"

using namespace sdb;
namespace fs = std::filesystem;

namespace {

MeasureOptions quick() {
  MeasureOptions o;
  o.reps = 2;
  o.min_time_s = 0.001;
  o.rays = 20000;
  return o;
}

}  // namespace

// Both Vulkan write probes measure something where there is a device, and nothing where there is
// none (the vulkan rows then have no bandwidth fraction).
TEST(Machine, VulkanWriteProbesRunWhereThereIsADevice) {
  const bool device = !describe_machine().vulkan_device.empty();
  const double fill = measure_gpu_write_bandwidth(), shader = measure_gpu_shader_write_bandwidth();
  EXPECT_EQ(fill > 0, device) << fill;
  EXPECT_EQ(shader > 0, device) << shader;
}

TEST(Results, RoundTripAndRefuseUnknownSchema) {
  ResultsFile r;
  r.machine.cpu_model = "test cpu";
  r.machine.gpu_shader_write_bandwidth_gbs = 4.5;
  r.created = "2026-11-21T00:00:00Z";
  RunRow row;
  row.scheme = "osd-bfr";
  row.mesh = "torus";
  row.time_ms.samples = {1.0, 2.0, 3.0};
  row.gpu_time_ms = TimeStats{1, 0.5, 2, 3, {0.5, 1, 2}};
  row.deviation.measured = true;
  row.deviation.pos_max_pct = 0.25;
  r.runs.push_back(row);
  const fs::path p = fs::temp_directory_path() / "sdb_results_test.json";
  write_results(r, p.string());
  const ResultsFile back = read_results(p.string());
  ASSERT_EQ(back.runs.size(), 1u);
  EXPECT_EQ(back.runs[0].time_ms.samples, row.time_ms.samples);
  EXPECT_DOUBLE_EQ(back.runs[0].deviation.pos_max_pct, 0.25);
  ASSERT_TRUE(back.runs[0].gpu_time_ms.has_value());
  EXPECT_EQ(back.machine.cpu_model, "test cpu");
  EXPECT_DOUBLE_EQ(back.machine.gpu_shader_write_bandwidth_gbs, 4.5);

  std::ofstream(p) << R"({"schema": 99, "runs": []})";
  try {
    read_results(p.string());
    FAIL() << "unknown schema accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown results schema 99"), std::string::npos);
  }
  std::ofstream(p) << "{ not json";
  EXPECT_THROW(read_results(p.string()), InputError);
}

TEST(Measure, ValidatesOnceAndTimesAPeer) {
  MeasureContext ctx(describe_machine());
  const RunRow row = measure_run({"osd-bfr", "torus-8x8", Backend::Cpu, 5}, quick(), ctx);
  EXPECT_EQ(row.status, RunStatus::Ok) << row.message;
  EXPECT_EQ(row.triangles, 64 * 2 * 16);
  EXPECT_EQ(row.tessellation, 4);
  EXPECT_EQ(row.watertight.open_edges, 0);
  EXPECT_EQ(row.watertight.ray_cracks, 0);
  EXPECT_EQ(row.watertight.rays, 40000);
  ASSERT_TRUE(row.deviation.measured);
  EXPECT_LE(row.deviation.pos_max_rel_diag, 1e-5);
  EXPECT_GE(row.deviation.hausdorff_rel, 0.0);
  EXPECT_EQ(row.time_ms.reps, 2);
  EXPECT_EQ(row.time_ms.samples.size(), 2u);
  EXPECT_GT(row.time_ms.median, 0.0);
  EXPECT_GT(row.triangle_rate_mtris, 0.0);
  EXPECT_EQ(row.bytes_out, static_cast<long>(row.vertices * 24));
}

TEST(Measure, UnsupportedBackendIsAStatusNotAFailure) {
  MeasureContext ctx(describe_machine());
  const RunRow row = measure_run({"osd-uniform", "cube", Backend::CpuMt, 2}, quick(), ctx);
  EXPECT_EQ(row.status, RunStatus::Unsupported);
  EXPECT_FALSE(row.message.empty());
}

// A run for its verdict only (the corpus scale-invariance test) leaves out the nearest-point
// deviation where no bound reads it (openmesh-cc declares none), and its verdict is the full run's.
TEST(Measure, VerdictOnlyRunLeavesOutTheDeviationNoBoundReads) {
  MeasureContext ctx(describe_machine());
  MeasureOptions o = quick();
  o.time = false, o.hausdorff = false;
  const RunRow full = measure_run({"openmesh-cc", "torus-8x8", Backend::Cpu, 2}, o, ctx);
  o.unjudged_deviation = false;
  const RunRow verdict = measure_run({"openmesh-cc", "torus-8x8", Backend::Cpu, 2}, o, ctx);
  ASSERT_TRUE(full.deviation.measured);
  EXPECT_EQ(full.deviation.measured_by, "nearest-point");
  EXPECT_FALSE(verdict.deviation.measured);
  EXPECT_EQ(verdict.status, full.status) << verdict.message;
  EXPECT_EQ(verdict.watertight.open_edges, full.watertight.open_edges);
  // Bounded at its coords, osd-bfr is measured either way.
  EXPECT_TRUE(measure_run({"osd-bfr", "torus-8x8", Backend::Cpu, 3}, o, ctx).deviation.measured);
}

// A scheme that only declares what faces it takes (prepare is never called here).
class FaceRequirement final : public Scheme {
 public:
  explicit FaceRequirement(bool split) { info_.name = split ? "splits" : "any", info_.accepts.split_polygons = split; }
  const SchemeInfo& info() const override { return info_; }
  std::unique_ptr<Evaluation> prepare(const ControlMesh&, const RunRequest&) const override { return nullptr; }

 private:
  SchemeInfo info_;
};

// Schemes that take a mesh differently (here: one splits pentagons, one takes them) never share
// the accepted mesh of one run (a cache keyed on the face kind alone handed the split-asking
// scheme the unsplit mesh).
TEST(Measure, EachFaceRequirementGetsItsOwnAcceptedMesh) {
  MeasureContext ctx(describe_machine());
  const FaceRequirement any(false), splits(true);
  std::shared_ptr<const ControlMesh> taken, split;
  try {
    taken = ctx.accepted("crane/spot_control", any);
  } catch (const InputError&) {
    GTEST_SKIP() << "no shared corpus";
  }
  split = ctx.accepted("crane/spot_control", splits);
  const auto largest = [](const ControlMesh& m) { return *std::max_element(m.face_sizes.begin(), m.face_sizes.end()); };
  EXPECT_EQ(largest(*taken), 5);
  EXPECT_EQ(largest(*split), 4);
}
