// The output's connectivity and surface coordinates: every sample of p^k is a vertex of the
// opened n x n grid (samples the cut fuses are separate, bit-identical vertices, so the exact
// weld closes the surface), triangulated along one diagonal.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "harness/core/tessellation.h"

namespace sdb::gim {

// Triangles over the n x n grid, vertex y * n + x, counter-clockwise in the image (so facing
// along T_s x T_t). Every quad of a quadrant is cut along the same diagonal, parallel to the edge
// of the unfolded octahedron in that quadrant (d-a, a-b, b-c, c-d): (x, y)-(x+1, y+1) in the
// top-right and bottom-left quadrants, (x+1, y)-(x, y+1) in the other two. Linear subdivision
// carries this triangulation onto the next level's, as Section 5 requires of its fixed diagonal
// direction; a single direction everywhere would, at each cut vertex, put a triangle across the
// 180-degree wedge of one of its two quads, a sliver that folds over (valence 2 leaves only two
// quads around it), while here both quads' diagonals run through the cut vertex.
std::vector<uint32_t> grid_triangles(int n);

// Whether quad (x, y) of an n x n grid uses the (x+1, y)-(x, y+1) diagonal.
inline bool anti_diagonal(int x, int y, int n) {
  const int h = (n - 1) / 2;
  return (x < h) == (y < h);
}

// SurfaceCoords (g0's quads, ptex u along image x, v along y) of the samples of level k of an
// n0 x n0 image: sample (x, y) is image point (x, y) / 2^k. k < 0 for subsampled levels.
std::vector<SurfaceCoord> grid_coords(int n0, int k);

// An evaluation's output for level k (n x n samples) of an n0 x n0 image of `g0`: triangles,
// coords and reference set, positions and normals sized for the subdivider to fill.
Tessellation grid_tessellation(int n0, int k, int n, std::shared_ptr<const ControlMesh> g0);

}  // namespace sdb::gim
