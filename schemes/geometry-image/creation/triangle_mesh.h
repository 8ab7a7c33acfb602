// The input surface as creation sees it: a closed genus-0 triangle mesh in double precision.
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "harness/core/control_mesh.h"
#include "schemes/geometry-image/octahedral_map.h"

namespace sdb::gim {

struct TriangleMesh {
  std::vector<Vec3d> positions;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside
};

// Polygons are split into triangles: quads along their shorter diagonal, larger polygons as a fan
// from their first vertex (the corpus holds a few pentagons; they are convex).
TriangleMesh triangulate(const ControlMesh& mesh);

// Splits every triangle into four at its edge midpoints. The surface is unchanged (the new
// vertices lie on the old triangles); a coarse mesh gets the degrees of freedom a low-stretch
// parametrization needs. New vertex k (after the old ones) is the midpoint of edge midpoints[k].
TriangleMesh refine_midpoints(const TriangleMesh& mesh, std::vector<std::pair<int, int>>* midpoints = nullptr);

// Throws InputError unless the mesh is one closed, manifold, genus-0 component; the message names
// the genus or the boundary it has.
void require_closed_genus0(const ControlMesh& mesh);

// Identifies a mesh's content (positions bit for bit, faces): the key of fitted images in the cache.
uint64_t content_hash(const ControlMesh& mesh);

// Per-vertex sorted, de-duplicated neighbour lists.
std::vector<std::vector<int>> vertex_neighbours(const TriangleMesh& mesh);
// Per-vertex incident triangles.
std::vector<std::vector<int>> vertex_triangles(const TriangleMesh& mesh);

double triangle_area(const Vec3d& a, const Vec3d& b, const Vec3d& c);
double surface_area(const TriangleMesh& mesh);
double bounding_box_diagonal(const std::vector<Vec3d>& points);

}  // namespace sdb::gim
