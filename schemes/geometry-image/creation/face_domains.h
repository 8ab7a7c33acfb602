// FaceDomains: where each point of the triangulated input lies on the input's own faces, so that
// creation samples the input's Catmull-Clark limit surface (what every other scheme draws) and
// not the flat control polygons the parametrization is computed on.
//
// Each triangle of triangulate() and refine_midpoints() lies in one base face; its corners carry
// positions in that face's domain, and a point of the triangle maps to the domain linearly (as
// it maps to the flat triangle). A quad's domain is its ptex square, corners (0,0), (1,0), (1,1),
// (0,1) in vertex order; any other face's is the regular polygon of as many sides, vertex j at
// angle 2 pi j / n, split into OpenSubdiv's ptex sub-quads (corner k at (0,0), the midpoint of
// edge k at (1,0), the centre at (1,1), the midpoint of edge k-1 at (0,1)) and mapped onto each
// by the inverse of the sub-quad's bilinear map. Both maps are linear along a face's edges, where
// they meet the neighbour's, so the sampled surface has no gap.
#pragma once

#include <array>
#include <vector>

#include "harness/core/control_mesh.h"
#include "harness/core/tessellation.h"
#include "schemes/geometry-image/octahedral_map.h"

namespace sdb::gim {

struct FaceDomains {
  std::vector<int> face;                      // per triangle: the base face it lies in
  std::vector<std::array<Vec2d, 3>> corners;  // per triangle: its corners in that face's domain
};

// The domains of triangulate(mesh)'s triangles, in its order.
FaceDomains face_domains(const ControlMesh& mesh, const std::vector<std::array<int, 3>>& triangles);

// The domains of refine_midpoints()'s triangles from those of the mesh it refined: triangle t's
// four children, in refine_midpoints' order, at 4t .. 4t + 3.
FaceDomains refine_domains(const FaceDomains& coarse);

// The ptex coordinate of a point of base face `face` (of `face_size` sides, its first ptex face
// `first_ptex`) at `domain` in the face's domain.
SurfaceCoord domain_coord(int face_size, int first_ptex, Vec2d domain);

}  // namespace sdb::gim
