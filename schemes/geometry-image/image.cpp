#include "schemes/geometry-image/image.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace sdb::gim {

CutSymmetry::CutSymmetry(int n) : n_(n) {
  if (n < 3 || n % 2 == 0)
    throw std::invalid_argument("a geometry image needs an odd size >= 3, not " + std::to_string(n));
  vertex_of_.assign(static_cast<size_t>(n) * n, -1);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      if (is_canonical(x, y)) vertex_of_[static_cast<size_t>(y) * n + x] = num_vertices_++;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const ImagePos c = canonical(x, y);
      vertex_of_[static_cast<size_t>(y) * n + x] = vertex_of_[static_cast<size_t>(c.y) * n + c.x];
    }
}

ImagePos CutSymmetry::fold(int x, int y) const {
  const int last = n_ - 1;
  // Each rule brings one coordinate back into range and mirrors the other within its range, so
  // a position at most one image away from the image folds in at most two steps.
  for (int guard = 0; guard < 64; ++guard) {
    if (y < 0) {
      x = last - x, y = -y;
    } else if (y > last) {
      x = last - x, y = 2 * last - y;
    } else if (x < 0) {
      x = -x, y = last - y;
    } else if (x > last) {
      x = 2 * last - x, y = last - y;
    } else {
      return {x, y};
    }
  }
  throw std::out_of_range("position too far outside the geometry image to fold");
}

ImagePos CutSymmetry::canonical(int x, int y) const {
  const ImagePos p = fold(x, y);
  const int last = n_ - 1;
  const bool left = p.x == 0, right = p.x == last, top = p.y == 0, bottom = p.y == last;
  if ((left || right) && (top || bottom)) return {0, 0};  // the four corners are the vertex x
  if (top || bottom) return {std::min(p.x, last - p.x), p.y};
  if (left || right) return {p.x, std::min(p.y, last - p.y)};
  return p;
}

int CutSymmetry::vertex(int x, int y) const {
  const ImagePos p = fold(x, y);
  return vertex_of_[static_cast<size_t>(p.y) * n_ + p.x];
}

std::array<ImagePos, 4> CutSymmetry::cut_vertices() const {
  const int h = half(), last = n_ - 1;
  return {ImagePos{h, 0}, ImagePos{last, h}, ImagePos{h, last}, ImagePos{0, h}};
}

// a's inward direction is +y and its along-border step -x; b, c, d are a's frame turned by
// successive quarter turns (x, y) -> (-y, x), which keep orientation, so one formula serves all.
ImagePos CutSymmetry::inward(int i) const {
  static constexpr ImagePos steps[4] = {{0, 1}, {-1, 0}, {0, -1}, {1, 0}};
  return steps[i];
}

ImagePos CutSymmetry::along(int i) const {
  static constexpr ImagePos steps[4] = {{-1, 0}, {0, -1}, {1, 0}, {0, 1}};
  return steps[i];
}

std::array<ImagePos, 4> CutSymmetry::cut_vertex_neighbours(int i) const {
  const ImagePos c = cut_vertices()[i], e = inward(i), u = along(i);
  return {ImagePos{c.x + u.x, c.y + u.y}, ImagePos{c.x + e.x, c.y + e.y}, ImagePos{c.x + u.x + e.x, c.y + u.y + e.y},
          ImagePos{c.x - u.x + e.x, c.y - u.y + e.y}};
}

std::vector<SymmetryViolation> cut_symmetry_violations(const GeometryImage& image, size_t max_report) {
  const CutSymmetry sym(image.size);
  std::vector<SymmetryViolation> out;
  for (int y = 0; y < image.size && out.size() < max_report; ++y)
    for (int x = 0; x < image.size && out.size() < max_report; ++x) {
      const ImagePos c = sym.canonical(x, y);
      const Point3& p = image.at(x, y);
      const Point3& q = image.at(c.x, c.y);
      for (int k = 0; k < 3; ++k)
        if (std::bit_cast<uint32_t>(p[k]) != std::bit_cast<uint32_t>(q[k])) {
          out.push_back({ImagePos{x, y}, c});
          break;
        }
    }
  return out;
}

void symmetrize(GeometryImage& image) {
  const CutSymmetry sym(image.size);
  for (int y = 0; y < image.size; ++y)
    for (int x = 0; x < image.size; ++x) {
      const ImagePos c = sym.canonical(x, y);
      image.at(x, y) = image.at(c.x, c.y);
    }
}

namespace {

Point3 neighbour_centroid(const GeometryImage& image, const CutSymmetry& sym, int i) {
  double s[3] = {0, 0, 0};
  for (const ImagePos& q : sym.cut_vertex_neighbours(i))
    for (int k = 0; k < 3; ++k) s[k] += image.at(q.x, q.y)[k];
  return {static_cast<float>(s[0] / 4), static_cast<float>(s[1] / 4), static_cast<float>(s[2] / 4)};
}

}  // namespace

void enforce_cut_vertex_centroids(GeometryImage& image) {
  const CutSymmetry sym(image.size);
  if (image.size < 5) return;  // a 3 x 3 image's cut vertices neighbour each other: nothing to solve
  for (int i = 0; i < 4; ++i) {
    const ImagePos c = sym.cut_vertices()[i];
    image.at(c.x, c.y) = neighbour_centroid(image, sym, i);
  }
}

double cut_vertex_centroid_residual(const GeometryImage& image) {
  const CutSymmetry sym(image.size);
  double worst = 0;
  for (int i = 0; i < 4; ++i) {
    const ImagePos c = sym.cut_vertices()[i];
    const Point3 m = neighbour_centroid(image, sym, i);
    const Point3& p = image.at(c.x, c.y);
    worst = std::max(worst, std::hypot(double(p[0]) - m[0], double(p[1]) - m[1], double(p[2]) - m[2]));
  }
  return worst;
}

}  // namespace sdb::gim
