// The run's plan and its worker's job lines (moved from harness/bench/bench_test.cpp with the run).
#include <gtest/gtest.h>

#include "harness/bench/machine.h"
#include "harness/bench/measure.h"
#include "harness/core/errors.h"
#include "harness/run/plan.h"
#include "harness/run/row_worker.h"

using namespace sdb;

TEST(Plan, DefaultSetSkipsRefusedMeshesAndHonoursTheBudget) {
  MeasureContext ctx(describe_machine());
  Selection sel;
  sel.schemes = {"osd-uniform-loop"};
  const Plan plan = make_plan(sel, ctx);
  ASSERT_FALSE(plan.runs.empty());
  bool icosphere = false;
  for (const auto& r : plan.runs) {
    EXPECT_NE(r.mesh, "cube") << "Loop refuses quads: skipped in the default set";
    icosphere |= r.mesh == "icosphere";
  }
  EXPECT_TRUE(icosphere);
  Selection big;
  big.schemes = {"osd-bfr"};
  big.meshes = {"frog-party"};
  big.max_triangles = 1'000'000;
  for (const auto& r : make_plan(big, ctx).runs) EXPECT_LE(r.level, 17) << "11628 quads at N=17 is 6M triangles";
  Selection pair;
  pair.schemes = {"osd-uniform-loop"};
  pair.meshes = {"cube"};
  EXPECT_THROW(make_plan(pair, ctx), InputError) << "an explicit refused pair is bad input";
}

// A row worker measures under the options run gave it: every field that shapes a row survives
// the job's JSON line (the worker once dropped the quick set's hausdorff_only_without_coords and
// computed a Hausdorff distance on every row).
TEST(RowWorker, OptionsReachTheWorkerWhole) {
  MeasureOptions o;
  o.reps = 7, o.min_time_s = 0.125, o.time = false, o.validate = false, o.hausdorff = false;
  o.hausdorff_only_without_coords = true, o.unjudged_deviation = false, o.rays = 1234, o.seed = 99, o.threads = 3;
  o.deviation_ply = "out.ply", o.refusals_as_rows = true;
  const MeasureOptions back = options_from_line(options_line(o));
  EXPECT_EQ(back.reps, 7);
  EXPECT_EQ(back.min_time_s, 0.125);
  EXPECT_FALSE(back.time);
  EXPECT_FALSE(back.validate);
  EXPECT_FALSE(back.hausdorff);
  EXPECT_TRUE(back.hausdorff_only_without_coords);
  EXPECT_FALSE(back.unjudged_deviation);
  EXPECT_EQ(back.rays, 1234);
  EXPECT_EQ(back.seed, 99u);
  EXPECT_EQ(back.threads, 3);
  EXPECT_EQ(back.deviation_ply, "out.ply");
  EXPECT_TRUE(back.refusals_as_rows);
}
