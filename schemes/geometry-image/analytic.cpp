#include "schemes/geometry-image/analytic.h"

#include <regex>

#include "harness/core/errors.h"
#include "schemes/geometry-image/closed_mesh.h"
#include "schemes/geometry-image/octahedral_map.h"

namespace sdb::gim {

GeometryImage analytic_image(AnalyticShape shape, int n) {
  const CutSymmetry sym(n);  // validates n
  GeometryImage image(n);
  const double one[3] = {1.0, 1.0, 1.0};
  const double* radii = shape == AnalyticShape::Sphere ? one : kEllipsoidRadii;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const Vec3d p = OctahedralMap::sphere_from_image(x, y, n);
      image.at(x, y) = {static_cast<float>(radii[0] * p[0]), static_cast<float>(radii[1] * p[1]),
                        static_cast<float>(radii[2] * p[2])};
    }
  // Identified samples agree to rounding only (cos(pi/2) is not 0); make them bit-identical.
  symmetrize(image);
  if (n >= 5) enforce_cut_vertex_centroids(image);
  return image;
}

std::optional<ControlMesh> analytic_mesh_from_name(const std::string& name) {
  std::smatch m;
  if (!std::regex_match(name, m, std::regex(R"(gim-(sphere|ellipsoid)-(\d+))"))) return std::nullopt;
  const int n = std::stoi(m[2].str());
  if (n < 5 || n % 2 == 0 || n > 4097)
    throw InputError(name, "a geometry image needs an odd size between 5 and 4097, not " + m[2].str());
  const AnalyticShape shape = m[1].str() == "sphere" ? AnalyticShape::Sphere : AnalyticShape::Ellipsoid;
  return closed_mesh(analytic_image(shape, n), name, "builtin:" + name);
}

}  // namespace sdb::gim
