// Helpers shared by the geometry-image tests.
#pragma once

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "datasets/manifest.h"
#include "harness/core/errors.h"
#include "schemes/geometry-image/analytic.h"
#include "schemes/geometry-image/creation/create.h"
#include "schemes/geometry-image/image.h"
#include "schemes/geometry-image/masks.h"

namespace sdb::gim::testing {

inline bool bits_equal(const Point3& a, const Point3& b) {
  for (int k = 0; k < 3; ++k)
    if (std::bit_cast<uint32_t>(a[k]) != std::bit_cast<uint32_t>(b[k])) return false;
  return true;
}

// Samples of an n x n grid that the cut identifies but that are not bit-identical.
inline long grid_symmetry_violations(const std::vector<Point3>& grid, int n) {
  const CutSymmetry sym(n);
  long bad = 0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const ImagePos c = sym.canonical(x, y);
      if (!bits_equal(grid[static_cast<size_t>(y) * n + x], grid[static_cast<size_t>(c.y) * n + c.x])) ++bad;
    }
  return bad;
}

// Positions of a padded image (border included) that are not bit-identical to the image sample
// the padding rules identify them with.
inline long padded_symmetry_violations(const PaddedImage& image) {
  const int n = image.side - 2;
  const CutSymmetry sym(n);
  long bad = 0;
  for (int row = 0; row < image.side; ++row)
    for (int col = 0; col < image.side; ++col) {
      const ImagePos c = sym.canonical(col - 1, row - 1);
      if (!bits_equal(image.at(col, row), image.at(c.x + 1, c.y + 1))) ++bad;
    }
  return bad;
}

// A wobbly closed surface as an image: the analytic ellipsoid with a smooth radial bump, so that
// no symmetry of the shape hides an indexing mistake. Cut-symmetric and with equation (2).
inline GeometryImage wobbly_image(int n, unsigned seed = 7) {
  GeometryImage image = analytic_image(AnalyticShape::Ellipsoid, n);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> phase(0.0f, 6.0f);
  const float a = phase(rng), b = phase(rng);
  for (Point3& p : image.samples) {
    const float s = 1.0f + 0.15f * std::sin(3.0f * p[0] + a) * std::cos(2.0f * p[1] + b) + 0.05f * p[2];
    p = {p[0] * s, p[1] * s, p[2] * s};
  }
  symmetrize(image);
  enforce_cut_vertex_centroids(image);
  return image;
}

inline std::string test_cache_dir() { return std::string(SDB_BINARY_DIR) + "/gim-cache"; }

// A corpus mesh, or nullopt when the shared corpus is absent.
inline std::optional<ControlMesh> corpus_mesh(const std::string& name) {
  if (!corpus_dir()) return std::nullopt;
  return load_mesh(name);
}

// The fitted image of a corpus mesh (cached under the build tree), or nullopt without the corpus.
inline std::optional<CreatedImage> fitted_image(const std::string& name, int n) {
  auto mesh = corpus_mesh(name);
  if (!mesh) return std::nullopt;
  CreationOptions options;
  options.size = n;
  options.cache_dir = test_cache_dir();
  return create_geometry_image(*mesh, options);
}

inline constexpr const char* kNoCorpus = "the shared corpus (../shared/datasets or $SUBDIVBENCH_DATASETS) is absent";

}  // namespace sdb::gim::testing
