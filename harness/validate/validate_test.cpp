#include <gtest/gtest.h>

#include <cmath>

#include "datasets/generators.h"
#include "harness/reference/dense_limit.h"
#include "harness/reference/limit_evaluator.h"
#include "harness/validate/deviation.h"
#include "harness/validate/watertight.h"

using namespace sdb;

namespace {

// The torus's limit at rate N (N - 1 segments a side), watertight: the surface the checks are tried on.
Tessellation limit_torus(int rate) {
  const ControlMesh torus = gen::torus(8, 12);
  Tessellation t = limit_tessellation(LimitEvaluator(torus, SubdivisionRule::CatmullClark), rate - 1);
  t.reference = std::make_shared<ControlMesh>(torus);
  return t;
}

// Gives one face its own copy of a border vertex (as patch schemes have), displaced by `offset`
// along x: zero keeps the surface closed, anything else opens a crack there. Returns the copy.
uint32_t split_border_vertex(Tessellation& t, float offset) {
  // A vertex on the border of ptex face 0 that is used by another face too.
  uint32_t target = ~0u;
  for (size_t i = 0; i < t.coords.size() && target == ~0u; ++i)
    if (t.coords[i].face != 0 && t.coords[i].u > 0 && t.coords[i].u < 1 && t.coords[i].v == 0) target = uint32_t(i);
  EXPECT_NE(target, ~0u);
  const uint32_t copy = static_cast<uint32_t>(t.positions.size());
  Point3 p = t.positions[target];
  p[0] = offset == 0 ? p[0] : p[0] + offset;
  t.positions.push_back(p);
  t.normals.push_back(t.normals[target]);
  t.coords.push_back(t.coords[target]);
  // Rewire the triangles of one of the two faces meeting there (those owned by the coord's face).
  const uint32_t face = t.coords[target].face;
  for (size_t i = 0; i + 2 < t.triangles.size(); i += 3) {
    bool of_face = true;
    for (int k = 0; k < 3; ++k) of_face &= t.coords[t.triangles[i + k]].face == face || t.triangles[i + k] == target;
    if (!of_face) continue;
    for (int k = 0; k < 3; ++k)
      if (t.triangles[i + k] == target) t.triangles[i + k] = copy;
  }
  return copy;
}

}  // namespace

TEST(ExactWeld, ClosedAndOpenSurfaces) {
  EXPECT_EQ(count_open_edges(limit_torus(5)), 0);
  Tessellation patch;
  patch.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  patch.triangles = {0, 1, 2, 0, 2, 3};
  EXPECT_EQ(count_open_edges(patch), 4);
}

TEST(ExactWeld, CatchesAOneUlpSplit) {
  Tessellation same = limit_torus(5);
  split_border_vertex(same, 0.0f);
  EXPECT_EQ(count_open_edges(same), 0) << "bit-identical copies must weld";
  Tessellation split = limit_torus(5);
  const uint32_t copy = split_border_vertex(split, 0.0f);
  split.positions[copy][0] = std::nextafter(split.positions[copy][0], 1e9f);
  EXPECT_GT(count_open_edges(split), 0);
}

TEST(RayCrackCheck, WatertightTorusHasNoCracks) {
  const RayCrackReport r = ray_crack_check(limit_torus(9), {100000, 100000, 42});
  EXPECT_EQ(r.rays, 200000);
  EXPECT_EQ(r.cracks, 0);
  EXPECT_EQ(r.seed, 42u);
}

TEST(RayCrackCheck, FindsAPlantedCrack) {
  Tessellation t = limit_torus(9);
  const float offset = static_cast<float>(1e-3 * bounds_of(t.positions).diagonal());
  split_border_vertex(t, offset);
  const RayCrackReport r = ray_crack_check(t, {100000, 100000, 42});
  EXPECT_GT(r.cracks, 0);
  EXPECT_EQ(count_open_edges(t), 4) << "the moved copy leaves both of its border edges open on each side";
}

TEST(Deviation, ReadsBackAPlantedOffset) {
  const ControlMesh torus = gen::torus(8, 12);
  const LimitEvaluator ref(torus, SubdivisionRule::CatmullClark);
  Tessellation t = limit_torus(5);
  const DeviationReport base = measure_deviation(t, ref);
  EXPECT_LE(base.pos_max_pct, 1e-3);
  // Move every vertex along its normal by 2% of its face's local size.
  for (size_t i = 0; i < t.positions.size(); ++i) {
    const double d = 0.02 * ref.local_size(static_cast<int>(t.coords[i].face));
    for (int k = 0; k < 3; ++k) t.positions[i][k] += static_cast<float>(d * t.normals[i][k]);
  }
  const DeviationReport moved = measure_deviation(t, ref);
  EXPECT_NEAR(moved.pos_max_pct, 2.0, 1e-3);
  EXPECT_NEAR(moved.pos_mean_pct, 2.0, 1e-3);
  EXPECT_NEAR(moved.pos_p95_pct, 2.0, 1e-3);
  // Tilt every normal by 3 degrees.
  const double a = 3.0 * M_PI / 180.0;
  for (auto& n : t.normals) {
    double tangent[3] = {n[1], -n[0], 0};  // torus normals are never parallel to z everywhere
    const double len = std::sqrt(tangent[0] * tangent[0] + tangent[1] * tangent[1]);
    if (len < 1e-6) continue;
    for (int k = 0; k < 3; ++k) n[k] = static_cast<float>(std::cos(a) * n[k] + std::sin(a) * tangent[k] / len);
  }
  const DeviationReport tilted = measure_deviation(t, ref);
  EXPECT_NEAR(tilted.normal_max_deg, 3.0, 0.01);
}

TEST(Hausdorff, ReadsBackAnOffsetSurface) {
  const Tessellation a = limit_torus(9);
  Tessellation b = a;
  const double diag = bounds_of(a.positions).diagonal(), delta = 1e-3 * diag;
  for (size_t i = 0; i < b.positions.size(); ++i)
    for (int k = 0; k < 3; ++k) b.positions[i][k] += static_cast<float>(delta * a.normals[i][k]);
  const HausdorffReport h = hausdorff(b, a);
  EXPECT_NEAR(h.forward_max, 1e-3, 1e-4);
  EXPECT_NEAR(h.forward_mean, 1e-3, 1e-4);
  EXPECT_NEAR(h.backward_mean, 1e-3, 1e-4);
  const HausdorffReport self = hausdorff(a, a);
  EXPECT_LE(self.max(), 1e-6);
}
