// Continuous level of detail (Section 5, "Continuous level-of-detail" and "Subsampling images").
//
// p^{k+alpha}, 0 < alpha <= 1, blends p^{k+1} with the linear subdivision of p^k, both on the
// grid of level k+1 and triangulated with fixed diagonal directions (one per quadrant,
// tessellation_grid.h) so that no diagonal flips between levels. As the paper does, p^k is not computed separately: its samples
// are gathered from p^{k+1} by subsampling (the limit points of g^k's vertices are the limit points
// of their children in g^{k+1}). Normals are blended the same way, then made unit (Tessellation
// asks for unit normals; the paper leaves them unnormalised for Gouraud shading).
//
// Negative levels: an image of size 2^j + 1 subsamples p^0 = E[g^0] down to p^{-(j-1)}, 3 x 3
// samples, the base octahedron; the blend works there unchanged.
#pragma once

#include <vector>

#include "harness/core/control_mesh.h"
#include "harness/core/tessellation.h"
#include "schemes/geometry-image/image.h"

namespace sdb::gim {

// A limit mesh on the opened n x n grid, row-major (vertex y * n + x).
struct LimitGrid {
  int size = 0;
  std::vector<Point3> positions, normals;
};

// Every other sample: size (n + 1) / 2. Requires n = 4i + 1 (i >= 1), so that the cut vertices,
// at (n - 1) / 2, stay on the coarse grid and it is a geometry image again.
LimitGrid subsample(const LimitGrid& fine);
// Linear subdivision of the triangulated grid: edge midpoints, and for each quad the midpoint of
// its diagonal (grid_triangles' choice). Size 2n - 1.
LimitGrid linear_subdivide(const LimitGrid& coarse);
// (1 - alpha) linear_subdivide(subsample(fine)) + alpha fine, normals made unit.
LimitGrid blend_levels(const LimitGrid& fine, double alpha);

// p^k of an image (k >= 0 by subdivision, k < 0 by subsampling p^0; the image size must allow it).
LimitGrid limit_grid(const GeometryImage& image, int k);
// The lowest level an n x n image reaches by subsampling: -(j - 1) for n = 2^j + 1 (down to the
// octahedron); in general the number of halvings while the size is 4i + 1.
int lowest_level(int n);

// p^level for a continuous level in [lowest_level(n), 6] as a Tessellation over the grid of level
// ceil(level), coords referring to the image's g0. Integer levels give p^level exactly.
Tessellation continuous_level_of_detail(const GeometryImage& image, double level);

}  // namespace sdb::gim
