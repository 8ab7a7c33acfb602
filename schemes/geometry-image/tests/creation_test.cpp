// Creation: topology checks, spherical parametrization, the fit, the cache.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "harness/reference/limit_evaluator.h"
#include "schemes/geometry-image/closed_mesh.h"
#include "schemes/geometry-image/creation/face_domains.h"
#include "schemes/geometry-image/creation/parametrize.h"
#include "schemes/geometry-image/octahedral_map.h"
#include "schemes/geometry-image/tests/test_support.h"

using namespace sdb;
using namespace sdb::gim;
using namespace sdb::gim::testing;

namespace {

std::string refusal(const ControlMesh& mesh) {
  try {
    GeometryImageCreator creator(mesh);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The dense samples of an image's own patch on the grid the fit uses.
DenseSamples samples_of_patch(const GeometryImage& image) {
  DenseSamples s;
  s.side = dense_sample_side(image.size);
  const double to_image = double(image.size - 1) / (s.side - 1);
  for (int j = 0; j < s.side; ++j)
    for (int i = 0; i < s.side; ++i) s.points.push_back(evaluate_patch(image, i * to_image, j * to_image));
  return s;
}

}  // namespace

// The limit samples' coordinates (face_domains.h) place a point of the triangulated input on its
// base face's limit: where triangles of different faces (and an n-gon's sub-quads) meet, the same
// point of the triangulation gives the same limit point from each side, so the sampled surface has
// no gap. Every corner of every triangle, twice refined, against every other that is the same vertex.
TEST(Creation, LimitSamplesAgreeWhereFacesMeet) {
  std::vector<std::string> names = {"pole5", "icosphere-1"};
  if (corpus_mesh("crane/spot_control")) names.push_back("crane/spot_control");  // quads and pentagons
  for (const std::string& name : names) {
    const ControlMesh mesh = load_mesh(name);
    const LimitEvaluator limit(mesh, SubdivisionRule::CatmullClark);
    TriangleMesh surface = triangulate(mesh);
    FaceDomains domains = face_domains(mesh, surface.triangles);
    for (int r = 0; r < 2; ++r) {
      surface = refine_midpoints(surface);
      domains = refine_domains(domains);
    }
    ASSERT_EQ(domains.face.size(), surface.triangles.size());
    std::vector<Vec3d> at(surface.positions.size());
    std::vector<char> seen(surface.positions.size(), 0);
    double worst = 0;
    long compared = 0;
    for (size_t t = 0; t < surface.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const int f = domains.face[t];
        const Vec3d p = limit.evaluate(domain_coord(mesh.face_sizes[f], limit.first_ptex_face(f), domains.corners[t][k])).position;
        const int v = surface.triangles[t][k];
        if (!seen[v]) {
          seen[v] = 1, at[v] = p;
          continue;
        }
        worst = std::max(worst, std::hypot(p[0] - at[v][0], p[1] - at[v][1], p[2] - at[v][2]));
        ++compared;
      }
    const double diagonal = bounds_of(mesh.positions).diagonal();
    std::printf("  %s: %ld shared corners, largest gap %.2e of the diagonal\n", name.c_str(), compared, worst / diagonal);
    EXPECT_GT(compared, long(surface.positions.size()));
    EXPECT_LT(worst / diagonal, 1e-6) << name;
  }
}

TEST(Creation, RefusesAGenusOneMeshAndAMeshWithBoundaryNamingWhy) {
  const std::string torus = refusal(load_mesh("torus"));
  EXPECT_NE(torus.find("genus 1"), std::string::npos) << torus;
  const std::string patch = refusal(load_mesh("open-patch"));
  EXPECT_NE(patch.find("boundary"), std::string::npos) << patch;
  EXPECT_NE(patch.find("boundary edges"), std::string::npos) << patch;
}

TEST(Creation, ParametrizesASphereNearlyIsometrically) {
  const TriangleMesh ico = triangulate(load_mesh("icosphere-3"));
  const SphericalParametrization p = SphericalParametrization::compute(ico);
  EXPECT_EQ(p.folded_triangles, 0);
  EXPECT_LT(p.stretch, 1.03);
  for (const Vec3d& q : p.sphere) EXPECT_NEAR(std::hypot(q[0], q[1], q[2]), 1.0, 1e-12);
}

TEST(Creation, ParametrizesAQuadMeshWithPolesAsAnEmbedding) {
  // A coarse quad mesh: refined before parametrizing, still one embedding with moderate stretch.
  const SphericalParametrization p = SphericalParametrization::compute(triangulate(load_mesh("pole7")));
  EXPECT_EQ(p.folded_triangles, 0);
  EXPECT_GE(p.surface.triangles.size(), SphericalParametrizationOptions{}.min_triangles);
  EXPECT_LT(p.stretch, p.centred_stretch + 1e-9);
  EXPECT_LT(p.stretch, 1.5);
}

TEST(Creation, FitRecoversAnImageFromItsOwnPatch) {
  // Samples of a bicubic patch that obeys the cut symmetry and equation (2) are fitted exactly
  // (without fairness): the fit's B-spline, padding and cut-vertex elimination are the surface's.
  const GeometryImage image = wobbly_image(9);
  FitOptions options;
  options.fairness = 0;
  FitReport report;
  const GeometryImage fitted = fit_geometry_image(9, samples_of_patch(image), options, &report);
  EXPECT_EQ(report.unknowns, 9 * 9 - 18 + 3 - 4);
  EXPECT_LT(report.rms_residual, 1e-6);
  for (size_t i = 0; i < image.samples.size(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(fitted.samples[i][c], image.samples[i][c], 2e-5);
  EXPECT_TRUE(cut_symmetry_violations(fitted).empty());
  EXPECT_LT(cut_vertex_centroid_residual(fitted), 1e-6);
}

TEST(Creation, FitApproximatesTheSphereThroughTheOctahedralMap) {
  const int n = 17;
  DenseSamples s;
  s.side = dense_sample_side(n);
  const double to_image = double(n - 1) / (s.side - 1);
  for (int j = 0; j < s.side; ++j)
    for (int i = 0; i < s.side; ++i) s.points.push_back(OctahedralMap::sphere_from_image(i * to_image, j * to_image, n));
  FitReport report;
  const GeometryImage fitted = fit_geometry_image(n, s, {}, &report);
  EXPECT_TRUE(cut_symmetry_violations(fitted).empty());
  // The residual compares points at equal parameters, and the equal-area map has kinks along the
  // octahedron's edges that a C2 patch cannot follow, so it is mostly tangential. The distance
  // from the sphere is what the fit achieves geometrically.
  double rms = 0, worst = 0;
  for (int j = 0; j < s.side; ++j)
    for (int i = 0; i < s.side; ++i) {
      const Vec3d p = evaluate_patch(fitted, i * to_image, j * to_image);
      const double e = std::abs(std::hypot(p[0], p[1], p[2]) - 1.0);
      rms += e * e, worst = std::max(worst, e);
    }
  rms = std::sqrt(rms / (s.side * s.side));
  std::printf("  sphere fitted by a 17x17 image: parametric rms %.2e, distance from the sphere rms %.2e max %.2e\n",
              report.rms_residual, rms, worst);
  EXPECT_LT(rms, 2e-3);
  EXPECT_LT(worst, 1e-2);
}

TEST(Creation, CachesImagesAndReadsThemBackBitForBit) {
  const std::string dir = test_cache_dir() + "/roundtrip";
  std::filesystem::remove_all(dir);
  CreationOptions options;
  options.size = 9;
  options.cache_dir = dir;
  GeometryImageCreator creator(load_mesh("pole5"), options);
  const CreatedImage first = creator.create(9);
  EXPECT_FALSE(first.report.from_cache);
  ASSERT_FALSE(first.report.cache_path.empty());
  EXPECT_TRUE(std::filesystem::exists(first.report.cache_path));
  EXPECT_GT(first.report.fit_ms, 0);
  const CreatedImage second = create_geometry_image(load_mesh("pole5"), options);
  EXPECT_TRUE(second.report.from_cache);
  EXPECT_EQ(second.report.cache_path, first.report.cache_path);
  EXPECT_DOUBLE_EQ(second.report.fit_ms, static_cast<float>(first.report.fit_ms));
  for (size_t i = 0; i < first.image.samples.size(); ++i)
    ASSERT_TRUE(bits_equal(first.image.samples[i], second.image.samples[i]));
  // Another mesh has another key.
  ControlMesh moved = load_mesh("pole5");
  moved.positions[0][0] += 0.25f;
  EXPECT_NE(GeometryImageCreator(moved, options).cache_key(), creator.cache_key());
  std::filesystem::remove_all(dir);
}

TEST(Creation, MakesImagesOfTheCorpusMeshes) {
  for (const char* name : {"crane/spot_low_resolution", "stanford/bunny", "crane/blub_control"}) {
    const auto made = fitted_image(name, 33);
    if (!made) GTEST_SKIP() << kNoCorpus;
    EXPECT_EQ(made->image.size, 33);
    EXPECT_TRUE(cut_symmetry_violations(made->image).empty()) << name;
    EXPECT_LT(cut_vertex_centroid_residual(made->image), 1e-5) << name;
    EXPECT_GT(made->report.stretch, 1.0) << name;
    EXPECT_LT(made->report.stretch, 2.5) << name;
    std::printf("  %s 33x33: %s parametrize %.0f ms (L2 stretch %.3f), sample %.0f ms, fit %.0f ms (CG %d)\n", name,
                made->report.from_cache ? "[cached]" : "", made->report.parametrize_ms, made->report.stretch,
                made->report.sample_ms, made->report.fit_ms, made->report.cg_iterations);
  }
}
