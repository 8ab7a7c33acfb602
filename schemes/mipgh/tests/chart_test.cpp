// Chart-morphic attributes (chart.h, Section 4, Figure 18):
//   - every level holds each chart's bilinear (quad) or linear (triangle) interpolation of its
//     corner values, as OpenSubdiv's face-varying FVAR_LINEAR_ALL refinement makes it;
//   - the list is per chart: independent corner values give a node on a D-edge one value per
//     D-facet; values shared at the vertices give every node one value, bit for bit;
//   - the displacement shader reads its texture coordinates from the list.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <random>

#include "datasets/generators.h"
#include "schemes/mipgh/atlas.h"
#include "schemes/mipgh/chart.h"
#include "schemes/mipgh/displacement.h"
#include "schemes/mipgh/lod.h"

using namespace sdb;
using namespace sdb::mipgh;

namespace {

constexpr int kDepth = 4;

// A square pyramid: one quad and four triangles, closed.
ControlMesh pyramid() {
  ControlMesh m;
  m.name = "pyramid";
  m.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {0, 0, 1}};
  m.face_sizes = {4, 3, 3, 3, 3};
  m.face_vertices = {0, 3, 2, 1, 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4};
  return m;
}

struct Case {
  ControlMesh mesh;
  FacetKinds kinds;
};

std::vector<Case> cases() {
  return {{gen::torus(6, 4), FacetKinds::Quads}, {gen::icosphere(1), FacetKinds::Triangles},
          {pyramid(), FacetKinds::QuadsAndTriangles}};
}

std::vector<std::array<ChartValue, 4>> random_corners(const DAtlas& atlas, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(0.0f, 1.0f);
  std::vector<std::array<ChartValue, 4>> corners(size_t(atlas.num_facets()));
  for (auto& c : corners)
    for (auto& v : c) v = {value(rng), value(rng)};
  return corners;
}

// Each D-facet corner takes its vertex's value: one texture coordinate per vertex, no seam.
std::vector<std::array<ChartValue, 4>> vertex_corners(const DAtlas& atlas) {
  std::vector<std::array<ChartValue, 4>> corners(size_t(atlas.num_facets()));
  for (int f = 0; f < atlas.num_facets(); ++f)
    for (int k = 0; k < atlas.facet_size[f]; ++k) {
      const int v = atlas.facet_corners[f][k];
      corners[size_t(f)][size_t(k)] = {float(v % 7) / 7.0f + 0.01f * float(v), float(v % 3) / 3.0f};
    }
  return corners;
}

// The chart's interpolation in double at node (i, j) of an N-node side.
std::array<double, 2> interpolated(const std::array<ChartValue, 4>& c, int size, int n, int i, int j) {
  const double u = double(j) / (n - 1), v = double(i) / (n - 1);
  std::array<double, 2> r{};
  for (int k = 0; k < 2; ++k)
    r[k] = size == 4 ? (1 - u) * (1 - v) * c[0][k] + u * (1 - v) * c[1][k] + u * v * c[2][k] + (1 - u) * v * c[3][k]
                     : (1 - u - v) * c[0][k] + u * c[1][k] + v * c[2][k];
  return r;
}

}  // namespace

TEST(ChartAttribute, EveryLevelIsEachChartsInterpolationOfItsCorners) {
  for (const Case& c : cases()) {
    const DAtlas atlas = build_atlas(c.mesh, c.kinds);
    const auto corners = random_corners(atlas, 7);
    const ChartAttribute chart(atlas, kDepth, corners);
    double worst = 0;
    for (int sigma = 0; sigma <= kDepth; ++sigma) {
      const int n = (1 << sigma) + 1;
      std::vector<char> used(chart.level(sigma).size(), 0);
      for (int f = 0; f < atlas.num_facets(); ++f) {
        const int size = atlas.facet_size[f];
        for (int i = 0; i < n; ++i)
          for (int j = 0; size == 4 ? j < n : i + j < n; ++j) {
            const uint32_t a = chart.address(sigma, f, {i, j});
            ASSERT_LT(a, used.size());
            EXPECT_FALSE(used[a]) << "two nodes hashed to one slot";
            used[a] = 1;
            const auto want = interpolated(corners[size_t(f)], size, n, i, j);
            for (int k = 0; k < 2; ++k) worst = std::max(worst, std::abs(double(chart.at(sigma, f, {i, j})[k]) - want[k]));
          }
      }
      EXPECT_EQ(std::count(used.begin(), used.end(), 1), long(used.size())) << "a slot no node hashes to";
    }
    EXPECT_LT(worst, 1e-6) << c.mesh.name;
  }
}

TEST(ChartAttribute, ANodeOnADEdgeHasOneValuePerDFacetAndOneValueWithoutASeam) {
  for (const Case& c : cases()) {
    const DAtlas atlas = build_atlas(c.mesh, c.kinds);
    const DLoD lod(atlas, kDepth);
    const int n = lod.layout(kDepth).n;
    for (bool seam : {true, false}) {
      const ChartAttribute chart(atlas, kDepth, seam ? random_corners(atlas, 11) : vertex_corners(atlas));
      std::map<uint32_t, ChartValue> first;  // node -> the first D-facet's value
      long shared = 0, differ = 0;
      for (int f = 0; f < atlas.num_facets(); ++f) {
        const int size = atlas.facet_size[f];
        for (int i = 0; i < n; ++i)
          for (int j = 0; size == 4 ? j < n : i + j < n; ++j) {
            const uint32_t node = lod.facet(kDepth, f)[facet_offset(size, n, {i, j})];
            const ChartValue& v = chart.at(kDepth, f, {i, j});
            const auto [it, inserted] = first.try_emplace(node, v);
            if (inserted) continue;
            ++shared;
            differ += std::memcmp(&it->second, &v, sizeof v) != 0;
          }
      }
      EXPECT_GT(shared, 0) << c.mesh.name;
      if (seam) EXPECT_EQ(differ, shared) << c.mesh.name << ": independent charts, a value per D-facet";
      else EXPECT_EQ(differ, 0) << c.mesh.name << ": charts agreeing at the vertices agree along every D-edge";
    }
  }
}

TEST(ChartAttribute, UnitChartsHoldTheNodesPlaceInTheDFacet) {
  const ControlMesh m = pyramid();
  const DAtlas atlas = build_atlas(m, FacetKinds::QuadsAndTriangles);
  const ChartAttribute chart = ChartAttribute::unit_charts(atlas, kDepth);
  const int n = (1 << kDepth) + 1;
  for (int f = 0; f < atlas.num_facets(); ++f)
    for (int i = 0; i < n; ++i)
      for (int j = 0; atlas.facet_size[f] == 4 ? j < n : i + j < n; ++j) {
        const ChartValue want{float(j) / float(n - 1), float(i) / float(n - 1)};  // dyadic: exact
        EXPECT_EQ(std::memcmp(&chart.at(kDepth, f, {i, j}), &want, sizeof want), 0) << f << " " << i << " " << j;
      }
}

TEST(ChartAttribute, DisplacementReadsItsTextureCoordinatesFromTheList) {
  const ControlMesh m = gen::torus(6, 4);
  const DAtlas atlas = build_atlas(m);
  const DLoD lod(atlas, 2);
  const uint32_t nodes = lod.layout(2).num_nodes;
  Tessellation t;
  t.positions.assign(nodes, {0, 0, 0});
  t.normals.assign(nodes, {0, 0, 1});
  // every corner at the bump's top, (0.5, 0.5): every node moves by the whole scale; unit charts
  // would leave the nodes on the D-facets' borders where they are
  const std::array<ChartValue, 4> top{{{0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, 0.5f}}};
  const ChartAttribute centre(atlas, 2, std::vector<std::array<ChartValue, 4>>(size_t(atlas.num_facets()), top));
  displace_along_normals(atlas, lod, 2, centre, bumps(65), 0.5f, t);
  for (const Point3& p : t.positions) EXPECT_NEAR(p[2], 0.5f, 1e-6f);
}
