#include "harness/pictures/framing.h"

#include <array>
#include <cmath>
#include <stdexcept>

namespace sdb::pictures {

Point3 view_direction(const Tessellation& t) {
  std::vector<std::array<double, 3>> area_vectors;  // twice each triangle's vector area
  area_vectors.reserve(t.num_triangles());
  const auto& p = t.positions;
  for (size_t i = 0; i + 2 < t.triangles.size(); i += 3) {
    const Point3 &a = p[t.triangles[i]], &b = p[t.triangles[i + 1]], &c = p[t.triangles[i + 2]];
    const double u[3] = {double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
    const double v[3] = {double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
    area_vectors.push_back({u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]});
  }
  auto projected = [&](const Point3& d) {
    double sum = 0;
    for (const auto& n : area_vectors) sum += std::abs(n[0] * d[0] + n[1] * d[1] + n[2] * d[2]);
    return sum;
  };
  const double pi = 3.14159265358979, elevation = 25 * pi / 180;
  const float length = std::sqrt(0.55f * 0.55f + 0.45f * 0.45f + 1.0f);  // frame_bounds' direction
  Point3 best{0.55f / length, 0.45f / length, 1.0f / length};
  double best_area = 1.05 * projected(best);
  for (int k = 0; k < 12; ++k) {
    const double azimuth = (15 + 30 * k) * pi / 180;
    const Point3 d{float(std::cos(elevation) * std::sin(azimuth)), float(std::sin(elevation)),
                   float(std::cos(elevation) * std::cos(azimuth))};
    const double area = projected(d);
    if (area > best_area) best = d, best_area = area;
  }
  return best;
}

gpu::Camera picture_camera(const std::vector<const Tessellation*>& surfaces, float aspect) {
  if (surfaces.empty()) throw std::invalid_argument("picture_camera: no surface to frame");
  std::vector<Point3> points;
  for (const Tessellation* t : surfaces) points.insert(points.end(), t->positions.begin(), t->positions.end());
  return gpu::frame_points(points, aspect, view_direction(*surfaces.front()));
}

}  // namespace sdb::pictures
