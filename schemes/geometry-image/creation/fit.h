// GeometryImageFit: the least-squares fit of an image's control points to dense samples of the
// surface (Section 4, "Fitting").
//
// Unknowns are the vertices of the closed mesh g0 (so the cut symmetry holds by construction)
// except a, b, c, d, which equation (2) defines as the centroids of their four neighbours and
// which are therefore eliminated, as the paper does. The objective is
//     (1/K) sum_k |P(s_k, t_k) - S_k|^2  +  (lambda / F) sum_v |g_v - centroid of v's 4 neighbours|^2
// over K dense samples S_k of the surface at image points (s_k, t_k) and the F free vertices:
// the paper's data term and its fairness functional, each normalised by its number of terms so
// that lambda is independent of the image and sample counts. P is the padded bicubic B-spline
// patch of Section 3. The normal equations are solved by Eigen's sparse conjugate gradients
// (Jacobi preconditioner), started from the samples at the image's own grid points.
#pragma once

#include <functional>
#include <vector>

#include "schemes/geometry-image/image.h"
#include "schemes/geometry-image/octahedral_map.h"

namespace sdb::gim {

// The surface sampled on a side x side grid over the image domain: point (i, j) is the surface at
// image coordinates (i, j) * (n - 1) / (side - 1), row-major.
struct DenseSamples {
  int side = 0;
  std::vector<Vec3d> points;
};

struct FitOptions {
  // lambda. 0.1 with four reprojections: on pole3..pole8 and the quad sphere at 65 x 65 no normal
  // more than 5 degrees from the limit's (0.03 folded pole7 and pole8 by 80 degrees; 0.3 and 1
  // kept them smooth and lost detail on Spot, Blub and the bunny); notes/2026-12-07-fit-to-the-limit.md.
  double fairness = 0.1;
  // Rounds of refitting, each to the surface's closest points to the fitted patch at the samples'
  // image coordinates (with a ClosestOnSurface; create.cpp). Two left pole8 within 10 degrees,
  // four within 5 and half the distance.
  int reprojections = 4;
  double tolerance = 1e-10;  // CG: relative residual of the normal equations
  int max_iterations = 10000;
};

struct FitReport {
  long samples = 0;
  int unknowns = 0;        // 3 coordinates each
  int iterations = 0;      // CG, largest over the three coordinates
  double cg_error = 0;     // CG's relative residual, largest over the coordinates
  double rms_residual = 0; // |P(s_k, t_k) - S_k| over the samples (the last closest points), root mean square
  double max_residual = 0;
};

// Samples per side of the dense grid for an n x n image: a multiple of (n - 1), plus one, so the
// image's grid points are among the samples, and at least 257.
int dense_sample_side(int n);

// The point of the surface being fitted closest to a point of the fitted patch. Thread-safe.
using ClosestOnSurface = std::function<Vec3d(const Vec3d&)>;

// With `closest`, the fit is then repeated options.reprojections times against the surface's
// closest points to the patch at the samples' image coordinates: the samples' parameters come from
// the parametrization, whose kinks (the octahedral map's edges, the spherical map's triangles) a
// C2 patch cannot follow, and a fit to them trades distance from the surface for parametric
// agreement and can fold where the map turns sharply; a fit to closest points measures only the
// distance. Samples, unknowns and the normal matrix stay; only the right-hand side changes.
GeometryImage fit_geometry_image(int n, const DenseSamples& samples, const FitOptions& options = {},
                                 FitReport* report = nullptr, const ClosestOnSurface& closest = {});

// The padded bicubic patch of `image` at image coordinates (s, t), in double precision.
Vec3d evaluate_patch(const GeometryImage& image, double s, double t);

}  // namespace sdb::gim
