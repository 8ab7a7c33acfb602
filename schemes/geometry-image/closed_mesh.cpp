#include "schemes/geometry-image/closed_mesh.h"

#include <algorithm>
#include <cmath>

namespace sdb::gim {

namespace {

// n from the vertex count n^2 - 2n + 3, or 0.
int size_from_vertex_count(int vertices) {
  if (vertices < 6) return 0;
  const int n = 1 + static_cast<int>(std::lround(std::sqrt(static_cast<double>(vertices - 2))));
  return n * n - 2 * n + 3 == vertices && n % 2 == 1 ? n : 0;
}

std::vector<int> quad_vertices(const CutSymmetry& sym) {
  const int n = sym.size();
  std::vector<int> fv;
  fv.reserve(static_cast<size_t>(n - 1) * (n - 1) * 4);
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      fv.push_back(sym.vertex(i, j));
      fv.push_back(sym.vertex(i + 1, j));
      fv.push_back(sym.vertex(i + 1, j + 1));
      fv.push_back(sym.vertex(i, j + 1));
    }
  return fv;
}

}  // namespace

ControlMesh closed_mesh(const GeometryImage& image, const std::string& name, const std::string& source) {
  const CutSymmetry sym(image.size);
  const int n = image.size;
  ControlMesh mesh;
  mesh.name = name;
  mesh.source = source;
  mesh.positions.resize(sym.num_vertices());
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      if (sym.is_canonical(x, y)) mesh.positions[sym.vertex(x, y)] = image.at(x, y);
  mesh.face_vertices = quad_vertices(sym);
  mesh.face_sizes.assign(static_cast<size_t>(n - 1) * (n - 1), 4);
  return mesh;
}

std::optional<GeometryImage> image_from_closed_mesh(const ControlMesh& mesh) {
  const int n = size_from_vertex_count(num_vertices(mesh));
  if (n == 0 || num_faces(mesh) != (n - 1) * (n - 1)) return std::nullopt;
  if (!std::all_of(mesh.face_sizes.begin(), mesh.face_sizes.end(), [](int s) { return s == 4; })) return std::nullopt;
  if (!mesh.creases.empty() || !mesh.corners.empty() || !mesh.holes.empty()) return std::nullopt;
  const CutSymmetry sym(n);
  if (mesh.face_vertices != quad_vertices(sym)) return std::nullopt;
  GeometryImage image(n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) image.at(x, y) = mesh.positions[sym.vertex(x, y)];
  return image;
}

SurfaceCoord surface_coord(double x, double y, int n) {
  const int i = std::clamp(static_cast<int>(std::floor(x)), 0, n - 2);
  const int j = std::clamp(static_cast<int>(std::floor(y)), 0, n - 2);
  return {static_cast<uint32_t>(j * (n - 1) + i), static_cast<float>(x - i), static_cast<float>(y - j)};
}

}  // namespace sdb::gim
