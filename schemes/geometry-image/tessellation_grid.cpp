#include "schemes/geometry-image/tessellation_grid.h"

#include <cmath>

#include "schemes/geometry-image/closed_mesh.h"

namespace sdb::gim {

std::vector<uint32_t> grid_triangles(int n) {
  std::vector<uint32_t> tris;
  tris.reserve(static_cast<size_t>(n - 1) * (n - 1) * 6);
  for (int y = 0; y + 1 < n; ++y)
    for (int x = 0; x + 1 < n; ++x) {
      const uint32_t v00 = y * n + x, v10 = v00 + 1, v01 = v00 + n, v11 = v01 + 1;
      if (anti_diagonal(x, y, n))
        tris.insert(tris.end(), {v00, v10, v01, v10, v11, v01});
      else
        tris.insert(tris.end(), {v00, v10, v11, v00, v11, v01});
    }
  return tris;
}

std::vector<SurfaceCoord> grid_coords(int n0, int k) {
  const int n = k >= 0 ? (n0 - 1) * (1 << k) + 1 : (n0 - 1) / (1 << -k) + 1;
  const double step = std::ldexp(1.0, -k);
  std::vector<SurfaceCoord> coords(static_cast<size_t>(n) * n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) coords[static_cast<size_t>(y) * n + x] = surface_coord(x * step, y * step, n0);
  return coords;
}

Tessellation grid_tessellation(int n0, int k, int n, std::shared_ptr<const ControlMesh> g0) {
  Tessellation out;
  out.positions.resize(static_cast<size_t>(n) * n);
  out.normals.resize(out.positions.size());
  out.triangles = grid_triangles(n);
  out.coords = grid_coords(n0, k);
  out.reference = std::move(g0);
  return out;
}

}  // namespace sdb::gim
