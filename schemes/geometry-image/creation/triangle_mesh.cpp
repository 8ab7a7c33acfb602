#include "schemes/geometry-image/creation/triangle_mesh.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include "harness/core/errors.h"
#include "harness/mesh/facts.h"

namespace sdb::gim {

namespace {

Vec3d to_double(const Point3& p) { return {p[0], p[1], p[2]}; }

double distance2(const Vec3d& a, const Vec3d& b) {
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return dx * dx + dy * dy + dz * dz;
}

}  // namespace

TriangleMesh triangulate(const ControlMesh& mesh) {
  TriangleMesh out;
  out.positions.reserve(mesh.positions.size());
  for (const Point3& p : mesh.positions) out.positions.push_back(to_double(p));
  const std::vector<int> off = face_offsets(mesh);
  for (int f = 0; f < num_faces(mesh); ++f) {
    const int* v = mesh.face_vertices.data() + off[f];
    const int size = mesh.face_sizes[f];
    if (size == 4) {
      const auto& p = out.positions;
      if (distance2(p[v[0]], p[v[2]]) <= distance2(p[v[1]], p[v[3]])) {
        out.triangles.push_back({v[0], v[1], v[2]});
        out.triangles.push_back({v[0], v[2], v[3]});
      } else {
        out.triangles.push_back({v[0], v[1], v[3]});
        out.triangles.push_back({v[1], v[2], v[3]});
      }
      continue;
    }
    for (int k = 1; k + 1 < size; ++k) out.triangles.push_back({v[0], v[k], v[k + 1]});
  }
  return out;
}

TriangleMesh refine_midpoints(const TriangleMesh& mesh, std::vector<std::pair<int, int>>* midpoints) {
  TriangleMesh finer;
  finer.positions = mesh.positions;
  std::map<std::pair<int, int>, int> index;
  if (midpoints) midpoints->clear();
  auto middle = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    auto [it, inserted] = index.try_emplace({key.first, key.second}, static_cast<int>(finer.positions.size()));
    if (inserted) {
      const Vec3d& p = mesh.positions[a];
      const Vec3d& q = mesh.positions[b];
      finer.positions.push_back({0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1]), 0.5 * (p[2] + q[2])});
      if (midpoints) midpoints->push_back({a, b});
    }
    return it->second;
  };
  for (const auto& t : mesh.triangles) {
    const int ab = middle(t[0], t[1]), bc = middle(t[1], t[2]), ca = middle(t[2], t[0]);
    finer.triangles.push_back({t[0], ab, ca});
    finer.triangles.push_back({ab, t[1], bc});
    finer.triangles.push_back({ca, bc, t[2]});
    finer.triangles.push_back({ab, bc, ca});
  }
  return finer;
}

void require_closed_genus0(const ControlMesh& mesh) {
  const std::string who = "geometry-image creation";
  require_manifold(mesh, who);
  const MeshFacts facts = compute_facts(mesh);
  const std::string where = mesh.source.empty() ? mesh.name : mesh.source;
  if (facts.boundary_edges > 0)
    throw InputError(where, who + " needs a closed mesh, and '" + mesh.name + "' has a boundary: " +
                                std::to_string(facts.boundary_edges) + " boundary edges in " +
                                std::to_string(facts.boundary_loops) + " loop(s)");
  if (facts.components != 1)
    throw InputError(where, who + " needs one connected surface, and '" + mesh.name + "' has " +
                                std::to_string(facts.components) + " components");
  if (facts.genus != 0)
    throw InputError(where, who + " needs a genus-0 surface (a sphere's topology), and '" + mesh.name +
                                "' has genus " + std::to_string(facts.genus));
  if (facts.unused_vertices > 0)
    throw InputError(where, who + " needs every vertex on the surface, and '" + mesh.name + "' has " +
                                std::to_string(facts.unused_vertices) + " unused vertices");
}

uint64_t content_hash(const ControlMesh& mesh) {
  uint64_t h = 1469598103934665603ull;  // FNV-1a, 64 bit
  auto mix = [&](uint32_t word) {
    for (int b = 0; b < 4; ++b) {
      h ^= (word >> (8 * b)) & 0xffu;
      h *= 1099511628211ull;
    }
  };
  mix(static_cast<uint32_t>(mesh.positions.size()));
  for (const Point3& p : mesh.positions)
    for (float c : p) mix(std::bit_cast<uint32_t>(c));
  mix(static_cast<uint32_t>(mesh.face_sizes.size()));
  for (int s : mesh.face_sizes) mix(static_cast<uint32_t>(s));
  for (int v : mesh.face_vertices) mix(static_cast<uint32_t>(v));
  return h;
}

std::vector<std::vector<int>> vertex_neighbours(const TriangleMesh& mesh) {
  std::vector<std::vector<int>> nb(mesh.positions.size());
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      nb[t[k]].push_back(t[(k + 1) % 3]);
      nb[t[k]].push_back(t[(k + 2) % 3]);
    }
  for (auto& list : nb) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return nb;
}

std::vector<std::vector<int>> vertex_triangles(const TriangleMesh& mesh) {
  std::vector<std::vector<int>> vt(mesh.positions.size());
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t)
    for (int v : mesh.triangles[t]) vt[v].push_back(t);
  return vt;
}

double triangle_area(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double x = e1[1] * e2[2] - e1[2] * e2[1], y = e1[2] * e2[0] - e1[0] * e2[2], z = e1[0] * e2[1] - e1[1] * e2[0];
  return 0.5 * std::sqrt(x * x + y * y + z * z);
}

double surface_area(const TriangleMesh& mesh) {
  double a = 0;
  for (const auto& t : mesh.triangles) a += triangle_area(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
  return a;
}

double bounding_box_diagonal(const std::vector<Vec3d>& points) {
  Vec3d lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  Vec3d hi{-lo[0], -lo[1], -lo[2]};
  for (const auto& p : points)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  return std::sqrt(distance2(lo, hi));
}

}  // namespace sdb::gim
