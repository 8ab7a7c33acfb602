// The mask passes: against OpenSubdiv's Catmull-Clark step, on linear images, the fused pass
// against L then A, and the cut symmetry bit for bit after every pass.
#include <gtest/gtest.h>
#include <opensubdiv/far/primvarRefiner.h>

#include <cmath>

#include "harness/mesh/osd_topology.h"
#include "schemes/geometry-image/closed_mesh.h"
#include "schemes/geometry-image/subdivision.h"
#include "schemes/geometry-image/tests/test_support.h"

using namespace sdb;
using namespace sdb::gim;
using namespace sdb::gim::testing;

namespace {

struct VertexD {
  double p[3];
  void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0.0; }
  void AddWithWeight(const VertexD& s, float w) {
    for (int k = 0; k < 3; ++k) p[k] += w * s.p[k];
  }
};

struct SubdivisionRun {
  std::vector<Point3> positions, normals;
};

// Runs `s` (made for `image`'s size) on the image; its padded levels stay readable in `s`.
SubdivisionRun subdivide(const GeometryImage& image, Subdivider& s) {
  const ControlMesh g0 = closed_mesh(image, "g0", "test");
  const int n = s.size(s.levels());
  SubdivisionRun r{std::vector<Point3>(static_cast<size_t>(n) * n), std::vector<Point3>(static_cast<size_t>(n) * n)};
  s.run(g0.positions.data(), r.positions.data(), r.normals.data(), SerialRows());
  return r;
}

double distance(const Point3& a, const Point3& b) {
  return std::hypot(double(a[0]) - b[0], double(a[1]) - b[1], double(a[2]) - b[2]);
}

}  // namespace

TEST(MaskPass, SplitThenAverageIsOneCatmullClarkStepAwayFromTheCutVertices) {
  namespace Far = OpenSubdiv::Far;
  const int n = 9;
  const GeometryImage image = wobbly_image(n);
  const ControlMesh g0 = closed_mesh(image, "g0", "test");
  auto refiner = make_refiner(g0, SubdivisionRule::CatmullClark);
  refiner->RefineUniform(Far::TopologyRefiner::UniformOptions(1));
  std::vector<VertexD> coarse(g0.positions.size()), fine(refiner->GetLevel(1).GetNumVertices());
  for (size_t v = 0; v < coarse.size(); ++v)
    for (int k = 0; k < 3; ++k) coarse[v].p[k] = g0.positions[v][k];
  VertexD* dst = fine.data();
  Far::PrimvarRefiner(*refiner).Interpolate(1, coarse.data(), dst);

  Subdivider s(n, 1, PassPlan::PerMask);
  subdivide(image, s);
  const PaddedImage& g1 = s.level(1);
  const Far::TopologyLevel& level0 = refiner->GetLevel(0);
  const CutSymmetry sym(n);
  int compared = 0, cut_vertices_differ = 0;
  for (int y = 0; y < 2 * n - 1; ++y)
    for (int x = 0; x < 2 * n - 1; ++x) {
      int child;
      const int cx = x / 2, cy = y / 2;
      if (x % 2 == 0 && y % 2 == 0) {
        child = level0.GetVertexChildVertex(sym.vertex(cx, cy));
      } else if (y % 2 == 0) {
        child = level0.GetEdgeChildVertex(level0.FindEdge(sym.vertex(cx, cy), sym.vertex(cx + 1, cy)));
      } else if (x % 2 == 0) {
        child = level0.GetEdgeChildVertex(level0.FindEdge(sym.vertex(cx, cy), sym.vertex(cx, cy + 1)));
      } else {
        child = level0.GetFaceChildVertex(cy * (n - 1) + cx);
      }
      const Point3 ours = g1.at(x + 1, y + 1);
      const Point3 osd = {float(fine[child].p[0]), float(fine[child].p[1]), float(fine[child].p[2])};
      bool at_cut_vertex = false;
      for (const ImagePos& c : sym.cut_vertices()) at_cut_vertex |= x == 2 * c.x && y == 2 * c.y;
      if (at_cut_vertex) {
        // Catmull-Clark's valence-2 vertex rule is not the tensor-product mask of equation (1).
        cut_vertices_differ += distance(ours, osd) > 1e-4;
        continue;
      }
      EXPECT_LT(distance(ours, osd), 2e-6) << "level-1 sample (" << x << ", " << y << ")";
      ++compared;
    }
  EXPECT_EQ(compared, (2 * n - 1) * (2 * n - 1) - 4);
  EXPECT_GT(cut_vertices_differ, 0);
}

TEST(MaskPass, LimitAndTangentMasksReproduceALinearImage) {
  // A padded image holding a linear function of (col, row), ignoring the cut: E reproduces it,
  // and T_s, T_t are its two gradients, so the normal is their unit cross product.
  const int side = 12;
  PaddedImage g(side);
  const double base[3] = {0.5, -1, 2}, ds[3] = {1, 0.2, 0.1}, dt[3] = {0.3, 1, -0.2};
  for (int c = 0; c < 3; ++c)
    for (int row = 0; row < side; ++row)
      for (int col = 0; col < side; ++col)
        g.plane(c)[row * side + col] = static_cast<float>(base[c] + ds[c] * col + dt[c] * row);
  const int n = side - 2;
  std::vector<Point3> p(n * n), nn(n * n);
  limit_pass(g, p.data(), {0, n});
  normal_pass(g, nn.data(), {0, n});
  const double cross[3] = {ds[1] * dt[2] - ds[2] * dt[1], ds[2] * dt[0] - ds[0] * dt[2], ds[0] * dt[1] - ds[1] * dt[0]};
  const double len = std::hypot(cross[0], cross[1], cross[2]);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(p[y * n + x][c], base[c] + ds[c] * (x + 1) + dt[c] * (y + 1), 2e-6);
        EXPECT_NEAR(nn[y * n + x][c], cross[c] / len, 1e-6);
      }
  // L and A keep it linear, at half the spacing.
  PaddedImage split(2 * side - 1), averaged(2 * side - 3);
  split_pass(g, split, {0, split.side});
  average_pass(split, averaged, {0, averaged.side});
  for (int row = 0; row < averaged.side; ++row)
    for (int col = 0; col < averaged.side; ++col)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(averaged.plane(c)[row * averaged.side + col],
                    base[c] + ds[c] * (col + 1) * 0.5 + dt[c] * (row + 1) * 0.5, 4e-6);
}

TEST(MaskPass, FusedEqualsSplitThenAverage) {
  const GeometryImage image = wobbly_image(9);
  Subdivider per_mask(9, 4, PassPlan::PerMask), fused(9, 4, PassPlan::Fused);
  const SubdivisionRun a = subdivide(image, per_mask);
  const SubdivisionRun b = subdivide(image, fused);
  for (int k = 0; k <= 4; ++k) {
    const PaddedImage &x = per_mask.level(k), &y = fused.level(k);
    ASSERT_EQ(x.side, y.side);
    for (size_t i = 0; i < x.data.size(); ++i) ASSERT_NEAR(x.data[i], y.data[i], 2e-6) << "level " << k;
  }
  for (size_t i = 0; i < a.positions.size(); ++i) {
    ASSERT_LT(distance(a.positions[i], b.positions[i]), 2e-6);
    ASSERT_LT(distance(a.normals[i], b.normals[i]), 1e-4);
  }
}

TEST(MaskPass, CutSymmetryHoldsBitForBitAfterEveryPass) {
  for (PassPlan plan : {PassPlan::PerMask, PassPlan::Fused})
    for (const GeometryImage& image : {wobbly_image(9), wobbly_image(17, 3), analytic_image(AnalyticShape::Ellipsoid, 31)}) {
      const int levels = image.size > 20 ? 4 : 5;
      Subdivider s(image.size, levels, plan);
      const SubdivisionRun r = subdivide(image, s);
      for (int k = 0; k <= levels; ++k)
        EXPECT_EQ(padded_symmetry_violations(s.level(k)), 0) << "n " << image.size << " level " << k;
      const int n = s.size(levels);
      EXPECT_EQ(grid_symmetry_violations(r.positions, n), 0);
      EXPECT_EQ(grid_symmetry_violations(r.normals, n), 0);
    }
}

TEST(MaskPass, NormalsAreUnitAndOutwardIncludingAtTheCutVertices) {
  const GeometryImage sphere = analytic_image(AnalyticShape::Sphere, 31);
  for (int k = 0; k <= 3; ++k) {
    Subdivider s(31, k, PassPlan::Fused);
    const SubdivisionRun r = subdivide(sphere, s);
    const int n = s.size(k);
    double worst = 1;
    for (size_t i = 0; i < r.positions.size(); ++i) {
      const Point3 &p = r.positions[i], &q = r.normals[i];
      EXPECT_NEAR(std::hypot(q[0], q[1], q[2]), 1.0, 1e-5);
      worst = std::min(worst, double(p[0] * q[0] + p[1] * q[1] + p[2] * q[2]) / std::hypot(p[0], p[1], p[2]));
    }
    EXPECT_GT(worst, 0.99) << "level " << k;
    const CutSymmetry sym(n);
    for (const ImagePos& c : sym.cut_vertices()) {
      const Point3 &p = r.positions[c.y * n + c.x], &q = r.normals[c.y * n + c.x];
      EXPECT_GT((p[0] * q[0] + p[1] * q[1] + p[2] * q[2]) / std::hypot(p[0], p[1], p[2]), 0.999) << "level " << k;
    }
  }
}

TEST(MaskPass, FusedLimitNormalPassEqualsTheSeparatePasses) {
  Subdivider s(17, 2, PassPlan::PerMask);
  subdivide(wobbly_image(17), s);
  const PaddedImage& g = s.level(2);
  const int n = g.side - 2;
  std::vector<Point3> p1(n * n), n1(n * n), p2(n * n), n2(n * n);
  limit_pass(g, p1.data(), {0, n});
  normal_pass(g, n1.data(), {0, n});
  limit_normal_pass(g, p2.data(), n2.data(), {0, n});
  for (int i = 0; i < n * n; ++i) {
    ASSERT_TRUE(bits_equal(p1[i], p2[i]));
    ASSERT_TRUE(bits_equal(n1[i], n2[i]));
  }
}
