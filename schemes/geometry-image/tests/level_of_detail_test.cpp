// Continuous level of detail, subsampling to the octahedron, and displacement.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "harness/validate/watertight.h"
#include "schemes/geometry-image/displacement.h"
#include "schemes/geometry-image/level_of_detail.h"
#include "schemes/geometry-image/tests/test_support.h"

using namespace sdb;
using namespace sdb::gim;
using namespace sdb::gim::testing;

namespace {

double max_distance(const std::vector<Point3>& a, const std::vector<Point3>& b) {
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i)
    worst = std::max(worst, std::hypot(double(a[i][0]) - b[i][0], double(a[i][1]) - b[i][1], double(a[i][2]) - b[i][2]));
  return worst;
}

}  // namespace

TEST(LevelOfDetail, SubsamplesImagesOfSizeTwoToTheJPlusOneDownToTheOctahedron) {
  EXPECT_EQ(lowest_level(33), -4);
  EXPECT_EQ(lowest_level(65), -5);
  EXPECT_EQ(lowest_level(5), -1);
  EXPECT_EQ(lowest_level(31), 0);
  EXPECT_EQ(lowest_level(21), -1);
  const GeometryImage image = wobbly_image(33);
  const LimitGrid octahedron = limit_grid(image, -4);
  ASSERT_EQ(octahedron.size, 3);
  std::set<std::array<float, 3>> distinct(octahedron.positions.begin(), octahedron.positions.end());
  EXPECT_EQ(distinct.size(), 6u) << "x, a, b, c, d and the centre";
  const Tessellation t = continuous_level_of_detail(image, -4);
  EXPECT_EQ(t.num_triangles(), 8u);
  EXPECT_EQ(count_open_edges(t), 0);
  EXPECT_THROW(limit_grid(image, -5), std::invalid_argument);
}

TEST(LevelOfDetail, IntegerLevelsAreTheLimitMeshesAndSubsamplingMatchesTheCoarseLevel) {
  const GeometryImage image = wobbly_image(17);
  for (int k : {-2, 0, 2}) {
    const Tessellation t = continuous_level_of_detail(image, k);
    const LimitGrid p = limit_grid(image, k);
    ASSERT_EQ(t.positions.size(), p.positions.size());
    for (size_t i = 0; i < p.positions.size(); ++i) ASSERT_TRUE(bits_equal(t.positions[i], p.positions[i]));
  }
  // p^k gathered from p^{k+1} is p^k computed directly, up to rounding (same surface points).
  EXPECT_LT(max_distance(subsample(limit_grid(image, 3)).positions, limit_grid(image, 2).positions), 1e-5);
}

TEST(LevelOfDetail, BlendRunsFromTheLinearlySubdividedCoarseLevelToTheFineLevel) {
  const GeometryImage image = wobbly_image(17);
  const LimitGrid fine = limit_grid(image, 2);
  const LimitGrid coarse = linear_subdivide(subsample(fine));
  EXPECT_EQ(max_distance(blend_levels(fine, 0.0).positions, coarse.positions), 0.0);
  EXPECT_EQ(max_distance(blend_levels(fine, 1.0).positions, fine.positions), 0.0);
  // Continuity across an integer level: just above k, the mesh is p^k linearly subdivided.
  for (int k : {-1, 1}) {
    const Tessellation at = continuous_level_of_detail(image, k);
    const LimitGrid at_grid{static_cast<int>(std::lround(std::sqrt(at.positions.size()))), at.positions, at.normals};
    const Tessellation above = continuous_level_of_detail(image, k + 1e-4);
    EXPECT_LT(max_distance(above.positions, linear_subdivide(at_grid).positions), 1e-4) << "level " << k;
  }
}

TEST(LevelOfDetail, BlendedAndSubsampledMeshesStayClosed) {
  const GeometryImage image = wobbly_image(33);
  for (double level : {-3.5, -0.25, 0.5, 1.7, 3.0}) {
    const Tessellation t = continuous_level_of_detail(image, level);
    const int n = static_cast<int>(std::lround(std::sqrt(t.positions.size())));
    EXPECT_EQ(grid_symmetry_violations(t.positions, n), 0) << "level " << level;
    EXPECT_EQ(count_open_edges(t), 0) << "level " << level;
    for (const Point3& q : t.normals) ASSERT_NEAR(std::hypot(q[0], q[1], q[2]), 1.0, 1e-5);
  }
}

TEST(Displacement, MovesAlongTheNormalAndKeepsTheSurfaceClosed) {
  const GeometryImage sphere = analytic_image(AnalyticShape::Sphere, 31);
  Tessellation t = continuous_level_of_detail(sphere, 3);
  const int n = static_cast<int>(std::lround(std::sqrt(t.positions.size())));
  std::vector<double> radius;
  for (const Point3& p : t.positions) radius.push_back(std::hypot(p[0], p[1], p[2]));
  // Constant d: every sample moves by d along its (nearly radial) normal.
  ScalarImage d{n, std::vector<float>(t.positions.size(), 0.1f)};
  std::vector<Point3> moved = t.positions;
  displace(d, moved, t.normals);
  for (size_t i = 0; i < moved.size(); ++i)
    EXPECT_NEAR(std::hypot(moved[i][0], moved[i][1], moved[i][2]), radius[i] + 0.1, 2e-3);
  // Bumps from a function of the limit point: identified samples get the same d, so it stays closed.
  ScalarImage bumps = scalar_image_from_function(
      n, t.positions, [](const Point3& p) { return 0.05f * std::sin(8.0f * p[0]) * std::cos(6.0f * p[2]); });
  symmetrize(bumps);
  displace(bumps, t.positions, t.normals);
  EXPECT_EQ(grid_symmetry_violations(t.positions, n), 0);
  EXPECT_EQ(count_open_edges(t), 0);
}
