// The surface the vulkan backend makes: closed after the exact weld (no open edge across the
// X-cut, no ray crack) and on OpenSubdiv's Catmull-Clark limit of g0 away from the cut vertices.
// The full matrix (k = 1..5, rays at every level) is run once by `subdivbench validate`; here a
// subset that keeps the test under a few seconds on lavapipe.
#include <gtest/gtest.h>

#include <cstdio>

#include "harness/gpu/testing.h"
#include "harness/validate/watertight.h"
#include "schemes/geometry-image/analytic.h"
#include "schemes/geometry-image/closed_mesh.h"
#include "schemes/geometry-image/geometry_image.h"
#include "schemes/geometry-image/tests/limit_comparison.h"
#include "schemes/geometry-image/tests/test_support.h"

using namespace sdb;
using namespace sdb::gim;
using namespace sdb::gim::testing;

namespace {

class GeometryImageVulkanSurface : public gpu::testing::VulkanTest {};

std::unique_ptr<Evaluation> on_vulkan(const GeometryImage& image, int level) {
  static const auto scheme = make_geometry_image_scheme();
  auto e = scheme->prepare(closed_mesh(image, "g0", "test"), default_request(scheme->info(), Backend::Vulkan, level));
  e->execute();
  return e;
}

// Open edges at k = 1..max_level, ray cracks (100,000 random lines, as many aimed at g0's quad
// borders) at `ray_level`.
void expect_closed(const std::string& name, const GeometryImage& image, int max_level, int ray_level) {
  for (int k = 1; k <= max_level; ++k) {
    const auto e = on_vulkan(image, k);
    const long open = count_open_edges(e->result());
    EXPECT_EQ(open, 0) << name << " k=" << k;
    if (k != ray_level) continue;
    const RayCrackReport rays = ray_crack_check(e->result(), {.random_lines = 100000, .border_lines = 100000});
    std::printf("  %-26s k=%d: %ld open edges, %ld cracks in %ld rays (seed %llu)\n", name.c_str(), k, open,
                rays.cracks, rays.rays, static_cast<unsigned long long>(rays.seed));
    EXPECT_GE(rays.rays, 100000);
    EXPECT_EQ(rays.cracks, 0) << name << " k=" << k << ", seed " << rays.seed;
  }
}

}  // namespace

TEST_F(GeometryImageVulkanSurface, WeldedAnalyticSphereIsClosedAcrossTheCut) {
  expect_closed("gim-sphere-31", analytic_image(AnalyticShape::Sphere, 31), 5, 3);
}

TEST_F(GeometryImageVulkanSurface, WeldedImagesOfTheCorpusAreClosedAcrossTheCut) {
  for (const char* name : {"crane/spot_low_resolution", "stanford/bunny", "crane/blub_control"}) {
    const auto made = fitted_image(name, 33);
    if (!made) GTEST_SKIP() << kNoCorpus;
    expect_closed(name + std::string(" (33x33)"), made->image, 4, 3);
  }
}

TEST_F(GeometryImageVulkanSurface, MatchesTheCatmullClarkLimitOfG0AwayFromTheCutVertices) {
  struct Case {
    std::string name;
    GeometryImage image;
    int max_level;
  };
  std::vector<Case> cases = {{"ellipsoid 31x31", analytic_image(AnalyticShape::Ellipsoid, 31), 3},
                             {"wobbly 17x17", wobbly_image(17), 3}};
  if (auto spot = fitted_image("crane/spot_low_resolution", 33)) cases.push_back({"Spot 33x33", spot->image, 2});
  for (const Case& c : cases)
    for (int k = 1; k <= c.max_level; ++k) {
      const auto e = on_vulkan(c.image, k);
      const LimitComparison r = compare_with_limit(e->result(), c.image.size);
      std::printf(
          "  %-16s k=%d: away from cut vertices max %.2e of the diagonal, normals %.2e deg (%ld samples); "
          "near them max %.2e, normals %.2f deg (%ld samples)\n",
          c.name.c_str(), k, r.away_max, r.away_normal_deg, r.away, r.near_max, r.near_normal_deg, r.near);
      EXPECT_LE(r.away_max, 1e-5) << c.name << " k=" << k;
      EXPECT_LE(r.away_normal_deg, 2e-3) << c.name << " k=" << k;
      EXPECT_EQ(r.no_reference_normal, 4) << "only at a, b, c, d";
      EXPECT_GT(r.away, r.near);
    }
}
