#include "schemes/geometry-image/displacement.h"

#include <stdexcept>

#include "schemes/geometry-image/image.h"

namespace sdb::gim {

void symmetrize(ScalarImage& d) {
  const CutSymmetry sym(d.size);
  for (int y = 0; y < d.size; ++y)
    for (int x = 0; x < d.size; ++x) {
      const ImagePos c = sym.canonical(x, y);
      d.values[static_cast<size_t>(y) * d.size + x] = d.values[static_cast<size_t>(c.y) * d.size + c.x];
    }
}

ScalarImage scalar_image_from_function(int n, const std::vector<Point3>& positions,
                                       const std::function<float(const Point3&)>& f) {
  if (positions.size() != static_cast<size_t>(n) * n) throw std::invalid_argument("displacement: grid size mismatch");
  ScalarImage d{n, std::vector<float>(positions.size())};
  for (size_t i = 0; i < positions.size(); ++i) d.values[i] = f(positions[i]);
  return d;
}

void displace(const ScalarImage& d, std::vector<Point3>& positions, const std::vector<Point3>& normals) {
  if (d.values.size() != positions.size() || normals.size() != positions.size())
    throw std::invalid_argument("displacement: grid size mismatch");
  for (size_t i = 0; i < positions.size(); ++i)
    for (int c = 0; c < 3; ++c) positions[i][c] += d.values[i] * normals[i][c];
}

}  // namespace sdb::gim
