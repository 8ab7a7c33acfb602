// The subdivided surface against the reference: OpenSubdiv's Catmull-Clark limit of g0, the exact
// weld and ray-crack checks, and the fitted surface's Hausdorff distance to its input mesh.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "harness/reference/limit_evaluator.h"
#include "harness/validate/deviation.h"
#include "harness/validate/watertight.h"
#include "schemes/geometry-image/closed_mesh.h"
#include "schemes/geometry-image/creation/triangle_mesh.h"
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

// The input mesh as a Tessellation (triangulated), the reference for Hausdorff distances.
Tessellation as_tessellation(const ControlMesh& mesh) {
  const TriangleMesh tri = triangulate(mesh);
  Tessellation t;
  t.positions = mesh.positions;
  for (const auto& f : tri.triangles)
    for (int v : f) t.triangles.push_back(static_cast<uint32_t>(v));
  return t;
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

TEST(Surface, FittedSurfacesLieCloseToTheirMeshes) {
  std::printf("  %-26s %5s %10s %10s %10s %12s %12s\n", "mesh", "m", "fit ms", "forward", "backward",
              "Hausdorff", "(of diagonal)");
  for (const char* name : {"crane/spot_low_resolution", "stanford/bunny", "crane/blub_control"}) {
    auto mesh = corpus_mesh(name);
    if (!mesh) {
      GTEST_SKIP() << kNoCorpus;
    }
    const Tessellation input = as_tessellation(*mesh);
    for (int m : {33, 65, 129}) {
      const auto made = fitted_image(name, m);
      // A level whose grid has about 513 samples a side stands for the limit surface.
      const int level = m == 33 ? 4 : m == 65 ? 3 : 2;
      const Subdivided s = subdivide(made->image, level);
      const HausdorffReport h = hausdorff(s.tessellation(), input);
      std::printf("  %-26s %5d %10.0f %10.4f %10.4f %12.4f %s\n", name, m, made->report.fit_ms, h.forward_max,
                  h.backward_max, h.max(), made->report.from_cache ? "(fit cached)" : "");
      if (std::string(name) == "crane/spot_low_resolution" && m == 65) {
        EXPECT_LT(h.max(), 0.02);
      }
      EXPECT_LT(h.max(), 0.05) << name << " m=" << m;
    }
  }
}
