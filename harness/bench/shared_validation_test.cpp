// One validation per output content (shared_validation.h): rows whose outputs are the same bytes
// share one verdict, named in validation_of; an output differing by one vertex is validated on
// its own.
#include <gtest/gtest.h>

#include <cmath>

#include "harness/bench/machine.h"
#include "harness/bench/measure.h"
#include "harness/core/registry.h"

using namespace sdb;

namespace {

MeasureOptions checks_only() {
  MeasureOptions o;
  o.time = false;
  o.rays = 20000;
  return o;
}

// osd-bfr's output on the 8 x 8 torus at N = 5, with the surfaces it is judged against.
struct Output {
  JudgedSurfaces surfaces;
  std::unique_ptr<Evaluation> eval;
  RunRow row;
};

Output output_of(MeasureContext& ctx, Backend backend) {
  const Scheme& scheme = *find_scheme("osd-bfr");
  Output out;
  out.surfaces = judged_surfaces("torus-8x8", scheme, ctx);
  out.eval = scheme.prepare(*out.surfaces.accepted, default_request(scheme.info(), backend, 5));
  execute_on(*out.eval, backend);
  out.row = describe_spec({"osd-bfr", "torus-8x8", backend, 5}, ctx.machine());
  return out;
}

void expect_same_figures(const RunRow& a, const RunRow& b) {
  EXPECT_EQ(a.watertight.open_edges, b.watertight.open_edges);
  EXPECT_EQ(a.watertight.rays, b.watertight.rays);
  EXPECT_EQ(a.watertight.ray_cracks, b.watertight.ray_cracks);
  EXPECT_EQ(a.deviation.pos_max_rel_diag, b.deviation.pos_max_rel_diag);
  EXPECT_EQ(a.deviation.pos_p95_pct, b.deviation.pos_p95_pct);
  EXPECT_EQ(a.deviation.normal_max_deg, b.deviation.normal_max_deg);
  EXPECT_EQ(a.status, b.status);
}

}  // namespace

// Two rows whose outputs are the same bytes: the second takes the first's verdict and names it;
// its figures are those a validation of its own output gives.
TEST(SharedValidation, IdenticalBytesShareOneValidation) {
  MeasureContext ctx(describe_machine(false));
  const MeasureOptions o = checks_only();
  const RunRow first = measure_run({"osd-bfr", "torus-8x8", Backend::Cpu, 5}, o, ctx);
  const RunRow second = measure_run({"osd-bfr", "torus-8x8", Backend::CpuMt, 5}, o, ctx);
  ASSERT_EQ(first.status, RunStatus::Ok) << first.message;
  EXPECT_EQ(first.validation_of, "");
  EXPECT_EQ(second.validation_of, first.name()) << "osd-bfr's cpu and cpu-mt outputs are expected to be the same bytes";
  EXPECT_EQ(ctx.validated_outputs().size(), 1u);  // one output kept: the second was not a new content

  MeasureContext fresh(describe_machine(false));
  const RunRow alone = measure_run({"osd-bfr", "torus-8x8", Backend::CpuMt, 5}, o, fresh);
  EXPECT_EQ(alone.validation_of, "");
  expect_same_figures(second, alone);
  EXPECT_GT(alone.watertight.rays, 0);
  EXPECT_TRUE(alone.deviation.measured);
}

// One vertex moved: not the same bytes, so validated on its own, and its figures show the move.
TEST(SharedValidation, OneVertexDifferentIsValidatedOnItsOwn) {
  MeasureContext ctx(describe_machine(false));
  const MeasureOptions o = checks_only();
  Output a = output_of(ctx, Backend::Cpu);
  validate_once(a.row, a.eval->result(), a.surfaces, o, ctx);
  ASSERT_EQ(a.row.validation_of, "");

  Output b = output_of(ctx, Backend::CpuMt);
  Tessellation moved = b.eval->result();
  ASSERT_TRUE(same_output(moved, a.eval->result()));
  moved.positions[7][0] = std::nextafter(moved.positions[7][0], 1e9f);  // one ulp, one vertex
  EXPECT_FALSE(same_output(moved, a.eval->result()));
  validate_once(b.row, moved, b.surfaces, o, ctx);
  EXPECT_EQ(b.row.validation_of, "");
  EXPECT_EQ(ctx.validated_outputs().size(), 2u);

  // Moved far enough to see: the deviation is its own, not the first row's.
  Output c = output_of(ctx, Backend::CpuMt);
  Tessellation far = c.eval->result();
  far.positions[7][0] += 0.05f;
  validate_once(c.row, far, c.surfaces, o, ctx);
  EXPECT_EQ(c.row.validation_of, "");
  EXPECT_GT(c.row.deviation.pos_max_rel_diag, 10 * a.row.deviation.pos_max_rel_diag);
}

// The same bytes under another subject (another level, or another bound) are not shared: the
// verdict depends on what the output is judged by.
TEST(SharedValidation, SameBytesOtherSubjectNotShared) {
  ValidatedOutputs kept;
  Tessellation t;
  t.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  t.triangles = {0, 1, 2};
  int input = 0, accepted = 0;
  const VerdictSubject subject{"s", "m", 2, &input, &accepted, {}, {}};
  kept.remember(subject, t, "s/cpu/m/2", Verdict{});
  ASSERT_NE(kept.find(subject, t), nullptr);
  EXPECT_EQ(kept.find(subject, t)->run, "s/cpu/m/2");
  VerdictSubject other_level = subject;
  other_level.level = 3;
  EXPECT_EQ(kept.find(other_level, t), nullptr);
  VerdictSubject other_bound = subject;
  other_bound.bound.pos_rel_diag = 1e-6;
  EXPECT_EQ(kept.find(other_bound, t), nullptr);
  VerdictSubject other_checks = subject;  // e.g. a verdict-only run against a full one
  other_checks.checks = "rays 100 seed 1";
  EXPECT_EQ(kept.find(other_checks, t), nullptr);
  Tessellation flipped = t;
  flipped.triangles = {0, 2, 1};
  EXPECT_EQ(kept.find(subject, flipped), nullptr);
  // Another scheme's output is kept instead: one scheme+mesh's outputs at a time.
  kept.remember({"s2", "m", 2, &input, &accepted, {}, {}}, t, "s2/cpu/m/2", Verdict{});
  EXPECT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept.find(subject, t), nullptr);
}
