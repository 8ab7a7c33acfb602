// The subdivided surface against the reference: OpenSubdiv's Catmull-Clark limit of g0, the exact
// weld and ray-crack checks, and the fitted surface's distance from its input's limit surface.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "harness/reference/dense_limit.h"
#include "harness/reference/limit_evaluator.h"
#include "harness/validate/deviation.h"
#include "harness/validate/limit_distance.h"
#include "harness/validate/watertight.h"
#include "schemes/geometry-image/closed_mesh.h"
#include "schemes/geometry-image/geometry_image.h"
#include "schemes/geometry-image/tests/limit_comparison.h"
#include "schemes/geometry-image/tests/test_support.h"

using namespace sdb;
using namespace sdb::gim;
using namespace sdb::gim::testing;

namespace {

struct Subdivided {
  std::unique_ptr<Evaluation> evaluation;
  const Tessellation& tessellation() const { return evaluation->result(); }
};

Subdivided subdivide(const GeometryImage& image, int level, Backend backend = Backend::Cpu) {
  static const auto scheme = make_geometry_image_scheme();
  Subdivided s{scheme->prepare(closed_mesh(image, "g0", "test"), default_request(scheme->info(), backend, level))};
  s.evaluation->execute();
  return s;
}

LimitComparison compare_with_limit(const GeometryImage& image, int level) {
  const Subdivided s = subdivide(image, level);
  return sdb::gim::testing::compare_with_limit(s.tessellation(), image.size);
}

}  // namespace

TEST(Surface, MatchesTheCatmullClarkLimitOfG0AwayFromTheCutVertices) {
  struct Case {
    std::string name;
    GeometryImage image;
    int max_level;
  };
  std::vector<Case> cases = {{"ellipsoid 31x31", analytic_image(AnalyticShape::Ellipsoid, 31), 3},
                             {"wobbly 17x17", wobbly_image(17), 4}};
  if (auto spot = fitted_image("crane/spot_low_resolution", 33)) cases.push_back({"Spot 33x33", spot->image, 2});
  for (const Case& c : cases)
    for (int k = 1; k <= c.max_level; ++k) {
      const LimitComparison r = compare_with_limit(c.image, k);
      std::printf("  %-16s k=%d: away from cut vertices max %.2e of the diagonal, normals %.2e deg (%ld samples); "
                  "near them max %.2e, normals %.2f deg (%ld samples, %ld without a reference normal)\n",
                  c.name.c_str(), k, r.away_max, r.away_normal_deg, r.away, r.near_max, r.near_normal_deg, r.near,
                  r.no_reference_normal);
      EXPECT_LE(r.away_max, 1e-5) << c.name << " k=" << k;
      EXPECT_LE(r.away_normal_deg, 2e-3) << c.name << " k=" << k;  // float32 tangents at level k
      EXPECT_EQ(r.no_reference_normal, 4) << "only at a, b, c, d";
      EXPECT_GT(r.away, r.near);
      EXPECT_LT(r.near_max, 0.05) << "sanity near the cut vertices, " << c.name << " k=" << k;
    }
}

TEST(Surface, WeldedAnalyticSphereIsClosedAcrossTheCut) {
  const GeometryImage sphere = analytic_image(AnalyticShape::Sphere, 31);
  for (int k = 1; k <= 5; ++k) {
    const Subdivided s = subdivide(sphere, k);
    EXPECT_EQ(count_open_edges(s.tessellation()), 0) << "k=" << k;
    if (k == 3) {
      const RayCrackReport rays = ray_crack_check(s.tessellation(), {.random_lines = 100000});
      EXPECT_GE(rays.rays, 100000);
      EXPECT_EQ(rays.cracks, 0) << "k=" << k << ", seed " << rays.seed;
    }
  }
}

TEST(Surface, WeldedImagesOfTheCorpusAreClosedAcrossTheCut) {
  for (const char* name : {"crane/spot_low_resolution", "stanford/bunny", "crane/blub_control"}) {
    const auto made = fitted_image(name, 33);
    if (!made) GTEST_SKIP() << kNoCorpus;
    for (int k = 1; k <= 5; ++k) {
      const Subdivided s = subdivide(made->image, k);
      EXPECT_EQ(count_open_edges(s.tessellation()), 0) << name << " k=" << k;
      if (k == 3) {
        const RayCrackReport rays = ray_crack_check(s.tessellation(), {.random_lines = 100000});
        EXPECT_GE(rays.rays, 100000);
        EXPECT_EQ(rays.cracks, 0) << name << " k=" << k << ", seed " << rays.seed;
      }
    }
  }
}

// What a fitted image of a real mesh gives up against the input's Catmull-Clark limit, at the
// sizes the scheme is run at: every vertex of a level with about 513 samples a side, by its
// distance to the closest point of the limit surface (the rows' figure), and the two-sided
// Hausdorff distance to a dense tessellation of the limit (what the image rounds off).
TEST(Surface, FittedSurfacesLieCloseToTheirInputsLimit) {
  std::printf("  %-26s %5s %10s %10s %10s %12s (of the diagonal)\n", "mesh", "m", "fit ms", "max", "p95", "Hausdorff");
  for (const char* name : {"crane/spot_low_resolution", "stanford/bunny", "crane/blub_control"}) {
    auto mesh = corpus_mesh(name);
    if (!mesh) {
      GTEST_SKIP() << kNoCorpus;
    }
    const LimitEvaluator limit(*mesh, SubdivisionRule::CatmullClark);
    const LimitProjector projector(limit);
    const DenseLimit dense = dense_limit(limit);
    for (int m : {33, 65, 129}) {
      const auto made = fitted_image(name, m);
      const int level = m == 33 ? 4 : m == 65 ? 3 : 2;
      const Subdivided s = subdivide(made->image, level);
      const LimitDistance d = distance_by_nearest_point(s.tessellation(), projector);
      const HausdorffReport h = hausdorff(s.tessellation(), dense.surface, *dense.scene);
      std::printf("  %-26s %5d %10.0f %10.5f %10.5f %12.5f %s\n", name, m, made->report.fit_ms, d.report.pos_max_rel_diag,
                  d.pos_p95_rel_diag, h.max(), made->report.from_cache ? "(fit cached)" : "");
      EXPECT_EQ(d.report.vertices, long(s.tessellation().num_vertices())) << "every vertex judged";
      // Larger images follow the surface more closely; the 95th percentile within half a percent.
      EXPECT_LT(d.pos_p95_rel_diag, 0.005) << name << " m=" << m;
      EXPECT_LT(h.max(), 0.05) << name << " m=" << m;
    }
  }
}
