#include "schemes/mipgh/adaptive.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace sdb::mipgh {
namespace {

using D3 = Eigen::Vector3d;

struct FacetGeometry {
  std::vector<D3> centroid, normal;  // normal: unit, or zero for a degenerate facet
};

FacetGeometry facet_geometry(const DAtlas& atlas, const std::vector<Point3>& x) {
  FacetGeometry g;
  for (int f = 0; f < atlas.num_facets(); ++f) {
    const int size = atlas.facet_size[f];
    D3 c = D3::Zero(), p[4];
    for (int k = 0; k < size; ++k) {
      const Point3& q = x[atlas.facet_corners[f][k]];
      p[k] = {q[0], q[1], q[2]};
      c += p[k] / size;
    }
    // a quad's normal across its diagonals, a triangle's across two sides
    const D3 n = size == 4 ? (p[2] - p[0]).cross(p[3] - p[1]) : (p[1] - p[0]).cross(p[2] - p[0]);
    g.centroid.push_back(c), g.normal.push_back(n.norm() > 0 ? D3(n.normalized()) : D3::Zero());
  }
  return g;
}

uint8_t clamp_level(double level, int depth) { return uint8_t(std::clamp(level, 0.0, double(depth))); }

}  // namespace

std::vector<uint8_t> facet_labels(const DAtlas& atlas, const std::vector<Point3>& positions, AdaptiveCriterion c,
                                  int depth) {
  const int F = atlas.num_facets();
  std::vector<uint8_t> labels(F, uint8_t(depth));
  if (c.kind == Refinement::Uniform || F == 0) return labels;
  const FacetGeometry g = facet_geometry(atlas, positions);
  const Bounds box = bounds_of(positions);
  switch (c.kind) {
    case Refinement::Region: {
      const double cut = box.lo[0] + c.extent * (box.hi[0] - box.lo[0]);
      for (int f = 0; f < F; ++f) labels[f] = g.centroid[f][0] <= cut ? uint8_t(depth) : 0;
      break;
    }
    case Refinement::Curvature: {
      std::vector<double> bend(F, 0.0);
      for (const DEdge& e : atlas.edges) {
        if (e.minor.null()) continue;
        const double cosine = std::clamp(g.normal[e.major.facet].dot(g.normal[e.minor.facet]), -1.0, 1.0);
        const double angle = std::acos(cosine);
        bend[e.major.facet] = std::max(bend[e.major.facet], angle);
        bend[e.minor.facet] = std::max(bend[e.minor.facet], angle);
      }
      const double full = c.extent * *std::max_element(bend.begin(), bend.end());
      for (int f = 0; f < F; ++f) labels[f] = full > 0 ? clamp_level(std::ceil(depth * bend[f] / full), depth) : 0;
      break;
    }
    default: {
      const double beyond = 0.25 * box.diagonal() / std::sqrt(3.0);
      const D3 eye{box.hi[0] + beyond, box.hi[1] + beyond, box.hi[2] + beyond};
      std::vector<double> distance(F);
      for (int f = 0; f < F; ++f) distance[f] = (g.centroid[f] - eye).norm();
      const double nearest = *std::min_element(distance.begin(), distance.end());
      for (int f = 0; f < F; ++f)
        labels[f] = clamp_level(depth - std::floor(std::log2(distance[f] / nearest) / c.extent), depth);
    }
  }
  return labels;
}

}  // namespace sdb::mipgh
