#include "schemes/geometry-image/analytic.h"

#include <charconv>
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
  // libstdc++'s regex recurses once per character (a 60,000-character name overflowed the stack);
  // no name of this form is longer.
  constexpr size_t kLongestName = 64;
  std::smatch m;
  if (name.size() > kLongestName || !std::regex_match(name, m, std::regex(R"(gim-(sphere|ellipsoid)-(\d+))")))
    return std::nullopt;
  // (n - 1)^2 faces: 2001 is the largest odd size within the 4 M faces any generated mesh may have.
  constexpr int kLargestSize = 2001;
  const std::string digits = m[2].str();
  int n = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
  if (ec != std::errc() || end != digits.data() + digits.size() || n < 5 || n % 2 == 0 || n > kLargestSize)
    throw InputError(name, "a geometry image needs an odd size between 5 and " + std::to_string(kLargestSize) +
                               " (at most 4 M faces), not " + digits.substr(0, 20) + (digits.size() > 20 ? "..." : ""));
  const AnalyticShape shape = m[1].str() == "sphere" ? AnalyticShape::Sphere : AnalyticShape::Ellipsoid;
  return closed_mesh(analytic_image(shape, n), name, "builtin:" + name);
}

}  // namespace sdb::gim
