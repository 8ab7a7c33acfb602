// OctahedralMap: the unit sphere <-> the square geometry-image domain, through the octahedron
// unfolded by the X-cut (Praun and Hoppe 2003; Losasso et al. 2003, Section 3).
//
// The square is [-1, 1]^2 with image coordinates (x, y) in [0, n-1]^2 mapped linearly onto it.
// Its centre is the pole +z, the inner diamond |u| + |v| <= 1 the upper hemisphere, the four
// corner triangles fold over to the lower hemisphere and the four corners meet at the pole -z
// (the cut vertex x). Side midpoints are the equator points +-x, +-y (a, b, c, d).
//
// Sphere and octahedron are related by the concentric equal-area map (the same construction as
// Clarberg 2008): within a face, L1 distance r from the face's pole maps to z = +-(1 - r^2) and
// the position along the diagonal to the azimuth. Equal area means a uniform grid on the square
// samples the sphere uniformly, which is what the fit wants of the sphere-to-square step; the
// paper uses a stretch-minimising map for it instead.
#pragma once

#include <array>

namespace sdb::gim {

using Vec3d = std::array<double, 3>;
using Vec2d = std::array<double, 2>;

struct OctahedralMap {
  // (u, v) in [-1, 1]^2 -> unit sphere. Points identified by the cut map to the same point.
  static Vec3d sphere_from_square(Vec2d uv);
  // Unit sphere -> one preimage in [-1, 1]^2 (on the cut, the one the formulas give first).
  static Vec2d square_from_sphere(Vec3d p);
  // Image coordinates of an n x n image (0..n-1, fractional allowed) <-> square.
  static Vec2d square_from_image(double x, double y, int n) {
    return {2.0 * x / (n - 1) - 1.0, 2.0 * y / (n - 1) - 1.0};
  }
  static Vec3d sphere_from_image(double x, double y, int n) { return sphere_from_square(square_from_image(x, y, n)); }
};

}  // namespace sdb::gim
