#include "schemes/geometry-image/octahedral_map.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sdb::gim {

namespace {

double sign_of(double v) { return v < 0 ? -1.0 : 1.0; }

}  // namespace

Vec3d OctahedralMap::sphere_from_square(Vec2d uv) {
  const double u = std::clamp(uv[0], -1.0, 1.0), v = std::clamp(uv[1], -1.0, 1.0);
  double au = std::abs(u), av = std::abs(v);
  const bool lower = au + av > 1.0;
  if (lower) {  // fold the corner triangle over onto its lower-hemisphere octahedron face
    const double fu = 1.0 - av, fv = 1.0 - au;
    au = fu, av = fv;
  }
  const double r = au + av;  // L1 distance from the face's pole, 0..1
  if (r <= 0.0) return {0.0, 0.0, lower ? -1.0 : 1.0};
  const double phi = 0.5 * std::numbers::pi * av / r;
  const double z = 1.0 - r * r;
  const double ring = r * std::sqrt(std::max(0.0, 2.0 - r * r));  // sqrt(1 - z^2)
  return {sign_of(u) * ring * std::cos(phi), sign_of(v) * ring * std::sin(phi), lower ? -z : z};
}

Vec2d OctahedralMap::square_from_sphere(Vec3d p) {
  const double len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  const double x = p[0] / len, y = p[1] / len, z = p[2] / len;
  const double r = std::sqrt(std::max(0.0, 1.0 - std::abs(z)));
  const double phi = std::atan2(std::abs(y), std::abs(x));  // 0..pi/2
  double av = r * phi / (0.5 * std::numbers::pi), au = r - av;
  if (z < 0) {  // unfold onto the corner triangle
    const double fu = 1.0 - av, fv = 1.0 - au;
    au = fu, av = fv;
  }
  return {sign_of(x) * au, sign_of(y) * av};
}

}  // namespace sdb::gim
