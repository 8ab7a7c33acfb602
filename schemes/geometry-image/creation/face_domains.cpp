#include "schemes/geometry-image/creation/face_domains.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sdb::gim {

namespace {

// Corner j of a face of n sides in its domain.
Vec2d domain_corner(int n, int j) {
  if (n == 4) {
    static constexpr Vec2d kSquare[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    return kSquare[j];
  }
  const double angle = 2.0 * M_PI * j / n;
  return {std::cos(angle), std::sin(angle)};
}

Vec2d mid(const Vec2d& a, const Vec2d& b) { return {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])}; }

// (u, v) with bilinear(a, b, c, d)(u, v) = p for a convex quad a, b, c, d (at (0,0), (1,0), (1,1),
// (0,1)), by Newton's method from its centre; clamped to the unit square.
Vec2d inverse_bilinear(const Vec2d& a, const Vec2d& b, const Vec2d& c, const Vec2d& d, const Vec2d& p) {
  double u = 0.5, v = 0.5;
  for (int iteration = 0; iteration < 32; ++iteration) {
    double f[2], fu[2], fv[2];
    for (int k = 0; k < 2; ++k) {
      f[k] = (1 - u) * (1 - v) * a[k] + u * (1 - v) * b[k] + u * v * c[k] + (1 - u) * v * d[k] - p[k];
      fu[k] = (1 - v) * (b[k] - a[k]) + v * (c[k] - d[k]);
      fv[k] = (1 - u) * (d[k] - a[k]) + u * (c[k] - b[k]);
    }
    const double det = fu[0] * fv[1] - fu[1] * fv[0];
    if (det == 0) break;
    const double du = (f[0] * fv[1] - f[1] * fv[0]) / det, dv = (fu[0] * f[1] - fu[1] * f[0]) / det;
    u -= du, v -= dv;
    if (std::abs(du) + std::abs(dv) < 1e-15) break;
  }
  return {std::clamp(u, 0.0, 1.0), std::clamp(v, 0.0, 1.0)};
}

}  // namespace

FaceDomains face_domains(const ControlMesh& mesh, const std::vector<std::array<int, 3>>& triangles) {
  FaceDomains out;
  out.face.reserve(triangles.size());
  out.corners.reserve(triangles.size());
  const std::vector<int> off = face_offsets(mesh);
  size_t t = 0;
  for (int f = 0; f < num_faces(mesh); ++f) {
    const int n = mesh.face_sizes[f];
    const int* v = mesh.face_vertices.data() + off[f];
    for (int i = 0; i < (n == 4 ? 2 : n - 2); ++i, ++t) {
      if (t >= triangles.size()) throw std::logic_error("face_domains: fewer triangles than the faces make");
      std::array<Vec2d, 3> corners;
      for (int k = 0; k < 3; ++k) {
        const int j = static_cast<int>(std::find(v, v + n, triangles[t][k]) - v);
        if (j == n) throw std::logic_error("face_domains: a triangle's corner is not its face's vertex");
        corners[k] = domain_corner(n, j);
      }
      out.face.push_back(f);
      out.corners.push_back(corners);
    }
  }
  if (t != triangles.size()) throw std::logic_error("face_domains: more triangles than the faces make");
  return out;
}

FaceDomains refine_domains(const FaceDomains& coarse) {
  FaceDomains fine;
  fine.face.reserve(4 * coarse.face.size());
  fine.corners.reserve(4 * coarse.corners.size());
  for (size_t t = 0; t < coarse.face.size(); ++t) {
    const auto& [a, b, c] = coarse.corners[t];
    const Vec2d ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
    for (const std::array<Vec2d, 3>& child : {std::array<Vec2d, 3>{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}}) {
      fine.face.push_back(coarse.face[t]);
      fine.corners.push_back(child);
    }
  }
  return fine;
}

SurfaceCoord domain_coord(int face_size, int first_ptex, Vec2d p) {
  const int n = face_size;
  if (n == 4)
    return {static_cast<uint32_t>(first_ptex), static_cast<float>(std::clamp(p[0], 0.0, 1.0)),
            static_cast<float>(std::clamp(p[1], 0.0, 1.0))};
  // Sub-quad k holds the directions within half a sector of corner k.
  const double sector = 2.0 * M_PI / n;
  const int k = ((static_cast<int>(std::lround(std::atan2(p[1], p[0]) / sector)) % n) + n) % n;
  const Vec2d corner = domain_corner(n, k);
  const Vec2d uv = inverse_bilinear(corner, mid(corner, domain_corner(n, (k + 1) % n)), {0, 0},
                                    mid(domain_corner(n, (k + n - 1) % n), corner), p);
  return {static_cast<uint32_t>(first_ptex + k), static_cast<float>(uv[0]), static_cast<float>(uv[1])};
}

}  // namespace sdb::gim
