// SphericalParametrization: a bijective map of a closed genus-0 triangle mesh onto the unit
// sphere with low stretch (Section 4's first step; the paper follows Praun and Hoppe 2003).
//
// Method (ours, not Praun and Hoppe's coarse-to-fine optimisation):
//   0. A coarse input (a control mesh of a hundred faces) is first split, each triangle into four
//      at its edge midpoints, until it has min_triangles: the surface does not change, but the
//      parametrization gets the freedom to stretch thin parts (fins, ears) out.
//   1. Tutte embedding with mean-value weights (Floater 2003) of the mesh minus the star of its
//      highest-valence vertex, the link placed on a circle. Positive weights and a convex
//      boundary make the planar map bijective.
//   2. Inverse stereographic projection, the removed vertex at the pole: a spherical embedding.
//   3. Moebius centring: the conformal automorphism of the sphere that puts the centroid of the
//      surface's area (vertex areas carried to the sphere) at the origin, undoing the
//      concentration the boundary choice caused. Steps 1-3 give a near-conformal map.
//   4. Stretch-driven reweighting (after Yoshizawa, Belyaev and Seidel 2004): the Tutte weights
//      towards each vertex are divided by a power of its stretch and steps 1-3 repeated, keeping
//      the best map. Each round is a global solve, so area moves across the whole mesh at once.
//   5. Relaxation that lowers Sander et al.'s L2 stretch of the map sphere -> surface (the metric
//      Praun and Hoppe minimise), plus inverse_weight times the same measure of the inverse map:
//      L2 stretch alone penalises only undersampling and leaves local minima with sliver-shaped
//      spherical triangles, which the fit then cannot follow (on Spot the inverse term halves
//      the Hausdorff distance of the fitted surface). Vertex by vertex (Gauss-Seidel), a
//      backtracking line search down the analytic gradient in the tangent plane. The energy grows
//      without bound as a spherical triangle's area goes to zero and a move that would fold a
//      triangle is refused, so the map stays an embedding.
// Spherical triangles are measured by their chords (flat triangles through the three points);
// "folded" means a chord triangle facing inwards, which would break the ray-cast sampling.
#pragma once

#include <vector>

#include "schemes/geometry-image/creation/triangle_mesh.h"

namespace sdb::gim {

struct SphericalParametrizationOptions {
  size_t min_triangles = 1000;  // step 0
  int reweighting_rounds = 20;  // step 4
  int max_sweeps = 2000;        // step 5
  double inverse_weight = 0.5;  // step 5
  // Stop when a sweep lowers the stretch energy by less than this fraction.
  double tolerance = 1e-5;
};

struct SphericalParametrization {
  TriangleMesh surface;           // the input, refined as step 0 says
  std::vector<Vec3d> sphere;      // unit vector per vertex of `surface`
  double centred_stretch = 0;     // L2 stretch after steps 1-3 (1 would be an isometry up to scale)
  double stretch = 0;             // after steps 4-5
  int sweeps = 0;                 // of step 5
  int folded_triangles = 0;       // chord triangles facing inwards: 0 for an embedding

  static SphericalParametrization compute(const TriangleMesh& mesh, const SphericalParametrizationOptions& options = {});
};

// Sander et al.'s L2 stretch of the map from the chord triangles of `sphere` to the mesh, with
// the spherical area scaled to the surface's: sqrt(sum A (|J|_F^2 / 2) / sum A) over triangles
// of surface area A; infinite when a triangle is folded.
double l2_stretch(const TriangleMesh& mesh, const std::vector<Vec3d>& sphere);

}  // namespace sdb::gim
