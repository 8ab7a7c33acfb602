// The closed control mesh g0 of a geometry image (Section 3): the image's quads with the borders
// fused by the cut symmetry. Its four corners are one vertex x of valence 4; a, b, c, d have
// valence 2; every other vertex has valence 4. It has n^2 - 2n + 3 vertices and (n-1)^2 quads.
//
// Vertex v is the v-th canonical image position in row-major order (CutSymmetry::vertex). Quad
// (i, j) (image cell [i, i+1] x [j, j+1]) is face j * (n-1) + i with vertices
// (i, j), (i+1, j), (i+1, j+1), (i, j+1), so OpenSubdiv's ptex (u, v) of the face runs along the
// image's x and y axes: image point (x, y) is face (floor x, floor y) at (u, v) = fractional parts.
// Oriented so that the image's s x t points out of the surface (outwards for images made by the
// octahedral map, whose square has the +z pole at the centre).
#pragma once

#include <optional>

#include "harness/core/control_mesh.h"
#include "harness/core/tessellation.h"
#include "schemes/geometry-image/image.h"

namespace sdb::gim {

ControlMesh closed_mesh(const GeometryImage& image, const std::string& name, const std::string& source);

// A mesh whose connectivity is exactly closed_mesh()'s for some size n is taken to be that
// geometry image (this is how analytic images and exported fitted images are recognised);
// anything else gives nullopt.
std::optional<GeometryImage> image_from_closed_mesh(const ControlMesh& mesh);

// The point (x, y) of g0's image, in image coordinates 0..n-1 (fractions allowed), as a
// SurfaceCoord of the closed mesh.
SurfaceCoord surface_coord(double x, double y, int n);

}  // namespace sdb::gim
