// The image, its cut symmetry, the octahedral map, g0 and the analytic images.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "harness/mesh/facts.h"
#include "schemes/geometry-image/analytic.h"
#include "schemes/geometry-image/closed_mesh.h"
#include "schemes/geometry-image/octahedral_map.h"
#include "schemes/geometry-image/tests/test_support.h"

using namespace sdb;
using namespace sdb::gim;
using namespace sdb::gim::testing;


TEST(CutSymmetry, PaddingRulesOfThePaperHold) {
  for (int n : {5, 7, 31, 33}) {
    const CutSymmetry sym(n);
    // Section 3 with m = n + 1 and 1-based g: g_{0,i} = g_{2,m-i}, g_{m,i} = g_{m-2,m-i},
    // g_{i,0} = g_{m-i,2}, g_{i,m} = g_{m-i,m-2}; here 0-based image (x, y) = g_{x+1, y+1}.
    for (int i = 0; i < n; ++i) {
      EXPECT_EQ(sym.vertex(-1, i), sym.vertex(1, n - 1 - i));
      EXPECT_EQ(sym.vertex(n, i), sym.vertex(n - 2, n - 1 - i));
      EXPECT_EQ(sym.vertex(i, -1), sym.vertex(n - 1 - i, 1));
      EXPECT_EQ(sym.vertex(i, n), sym.vertex(n - 1 - i, n - 2));
      // The boundary conditions: each side is symmetric about its midpoint.
      EXPECT_EQ(sym.vertex(i, 0), sym.vertex(n - 1 - i, 0));
      EXPECT_EQ(sym.vertex(0, i), sym.vertex(0, n - 1 - i));
      EXPECT_EQ(sym.vertex(n - 1, i), sym.vertex(n - 1, n - 1 - i));
      EXPECT_EQ(sym.vertex(i, n - 1), sym.vertex(n - 1 - i, n - 1));
    }
    EXPECT_EQ(sym.vertex(0, 0), sym.vertex(n - 1, n - 1));
    EXPECT_EQ(sym.vertex(-1, -1), sym.vertex(n - 2, n - 2));  // the transitively applied rules
    EXPECT_EQ(sym.num_vertices(), n * n - 2 * n + 3);
  }
  EXPECT_THROW(CutSymmetry(4), std::invalid_argument);
}

TEST(ClosedMesh, IsAClosedGenusZeroQuadMeshWithFourValenceTwoVertices) {
  for (int n : {3, 5, 9, 31}) {
    const GeometryImage image = analytic_image(AnalyticShape::Ellipsoid, n);
    const ControlMesh g0 = closed_mesh(image, "g0", "test");
    const MeshFacts f = compute_facts(g0);
    EXPECT_TRUE(f.closed) << n;
    EXPECT_TRUE(f.manifold()) << n;
    EXPECT_EQ(f.genus, 0) << n;
    EXPECT_EQ(f.components, 1) << n;
    EXPECT_TRUE(f.all_quads) << n;
    EXPECT_EQ(f.faces, (n - 1) * (n - 1)) << n;
    EXPECT_EQ(f.valences.at(2), 4) << "a, b, c, d";
    EXPECT_EQ(f.valences.size(), 2u) << "only valences 2 and 4";
    EXPECT_EQ(f.valences.at(4), f.vertices - 4);
    EXPECT_GT(signed_volume6(g0), 0.0) << "g0 must face outwards, n = " << n;
  }
}

TEST(ClosedMesh, RecognisesItsOwnLayoutAndNothingElse) {
  const GeometryImage image = wobbly_image(9);
  const ControlMesh g0 = closed_mesh(image, "g0", "test");
  const auto back = image_from_closed_mesh(g0);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->size, 9);
  for (size_t i = 0; i < image.samples.size(); ++i) EXPECT_TRUE(bits_equal(back->samples[i], image.samples[i]));
  EXPECT_FALSE(image_from_closed_mesh(load_mesh("quadsphere")));
  EXPECT_FALSE(image_from_closed_mesh(load_mesh("cube")));
  ControlMesh shuffled = g0;
  std::swap(shuffled.face_vertices[0], shuffled.face_vertices[1]);
  EXPECT_FALSE(image_from_closed_mesh(shuffled));
}

TEST(ClosedMesh, SurfaceCoordsFollowTheImageAxes) {
  const int n = 7;
  const SurfaceCoord c = surface_coord(2.25, 3.5, n);
  EXPECT_EQ(c.face, 3u * (n - 1) + 2);
  EXPECT_FLOAT_EQ(c.u, 0.25f);
  EXPECT_FLOAT_EQ(c.v, 0.5f);
  const SurfaceCoord last = surface_coord(n - 1, n - 1, n);  // the far corner: last quad, (1, 1)
  EXPECT_EQ(last.face, static_cast<uint32_t>((n - 1) * (n - 1) - 1));
  EXPECT_FLOAT_EQ(last.u, 1.0f);
  EXPECT_FLOAT_EQ(last.v, 1.0f);
}

TEST(OctahedralMap, IsABijectionThatFusesTheCut) {
  for (double u = -1.0; u <= 1.0; u += 0.0625)
    for (double v = -1.0; v <= 1.0; v += 0.0625) {
      const Vec3d p = OctahedralMap::sphere_from_square({u, v});
      EXPECT_NEAR(std::hypot(p[0], p[1], p[2]), 1.0, 1e-12);
      const Vec2d back = OctahedralMap::square_from_sphere(p);
      const Vec3d again = OctahedralMap::sphere_from_square(back);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(again[k], p[k], 1e-12);
      // Off the cut the preimage is unique.
      if (std::abs(u) < 1 && std::abs(v) < 1) {
        EXPECT_NEAR(back[0], u, 1e-9);
        EXPECT_NEAR(back[1], v, 1e-9);
      }
    }
  // Each side's mirror images are one point; the corners are the pole -z; the centre +z.
  for (double t = 0; t <= 1.0; t += 0.125) {
    const Vec3d a = OctahedralMap::sphere_from_square({t, 1}), b = OctahedralMap::sphere_from_square({-t, 1});
    const Vec3d c = OctahedralMap::sphere_from_square({1, t}), d = OctahedralMap::sphere_from_square({1, -t});
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(a[k], b[k], 1e-12);
      EXPECT_NEAR(c[k], d[k], 1e-12);
    }
  }
  EXPECT_NEAR(OctahedralMap::sphere_from_square({1, 1})[2], -1.0, 1e-12);
  EXPECT_NEAR(OctahedralMap::sphere_from_square({0, 0})[2], 1.0, 1e-12);
}

TEST(OctahedralMap, IsEqualArea) {
  // The spherical areas of the images of equal squares agree (to the chord approximation).
  const int cells = 32;
  double lo = 1e9, hi = 0;
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      // Area of the image of the cell by the parallelogram of its mapped edges, sampled finely.
      double area = 0;
      const int sub = 8;
      for (int b = 0; b < sub; ++b)
        for (int a = 0; a < sub; ++a) {
          auto at = [&](int da, int db) {
            return OctahedralMap::sphere_from_image(i + (a + da) / double(sub), j + (b + db) / double(sub), cells + 1);
          };
          const Vec3d p = at(0, 0), q = at(1, 0), r = at(0, 1), s = at(1, 1);
          auto tri = [](const Vec3d& x, const Vec3d& y, const Vec3d& z) {
            const double e1[3] = {y[0] - x[0], y[1] - x[1], y[2] - x[2]}, e2[3] = {z[0] - x[0], z[1] - x[1], z[2] - x[2]};
            return 0.5 * std::hypot(e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]);
          };
          area += tri(p, q, s) + tri(p, s, r);
        }
      lo = std::min(lo, area), hi = std::max(hi, area);
    }
  EXPECT_LT(hi / lo, 1.02);
  EXPECT_NEAR(hi * cells * cells, 4 * std::numbers::pi, 0.05 * 4 * std::numbers::pi);
}

TEST(AnalyticImage, IsCutSymmetricBitForBitOnTheSphereWithEquationTwo) {
  for (AnalyticShape shape : {AnalyticShape::Sphere, AnalyticShape::Ellipsoid}) {
    const GeometryImage image = analytic_image(shape, 31);
    EXPECT_TRUE(cut_symmetry_violations(image).empty());
    EXPECT_LT(cut_vertex_centroid_residual(image), 1e-6);
    const CutSymmetry sym(31);
    for (int y = 0; y < 31; ++y)
      for (int x = 0; x < 31; ++x) {
        bool cut = false;
        for (const ImagePos& c : sym.cut_vertices()) cut |= c == ImagePos{x, y};
        if (cut) continue;
        const Point3& p = image.at(x, y);
        const double* r = shape == AnalyticShape::Sphere ? nullptr : kEllipsoidRadii;
        const double q = r ? std::hypot(p[0] / r[0], p[1] / r[1], p[2] / r[2]) : std::hypot(p[0], p[1], p[2]);
        EXPECT_NEAR(q, 1.0, 1e-6);
      }
  }
}

TEST(AnalyticImage, ManifestNamesGiveG0) {
  const ControlMesh m = load_mesh("gim-sphere-31");
  EXPECT_EQ(num_vertices(m), 31 * 31 - 62 + 3);
  EXPECT_EQ(num_faces(m), 900);
  ASSERT_TRUE(image_from_closed_mesh(m));
  const ControlMesh e = load_mesh("gim-ellipsoid-17");
  EXPECT_EQ(e.name, "gim-ellipsoid-17");
  EXPECT_TRUE(image_from_closed_mesh(e));
  EXPECT_THROW(load_mesh("gim-sphere-32"), InputError);
  EXPECT_THROW(load_mesh("gim-sphere-3"), InputError);
}

// Found with tests/fuzz's mesh-name target: a size past int was std::stoi's out_of_range (exit 3),
// sizes past 4 M faces were generated, and a long name overflowed the regex's recursion.
TEST(AnalyticImage, NamesAreCheckedBeforeAnythingIsGenerated) {
  EXPECT_THROW(load_mesh("gim-sphere-11111111111111111111"), InputError);
  EXPECT_THROW(load_mesh("gim-sphere-2003"), InputError);
  EXPECT_EQ(num_faces(*analytic_mesh_from_name("gim-sphere-5")), 16);
  EXPECT_FALSE(analytic_mesh_from_name("gim-sphere-" + std::string(60000, '1')).has_value());
}
