// The output's connectivity and surface coordinates: every sample of p^k is a vertex of the
// opened n x n grid (samples the cut fuses are separate, bit-identical vertices, so the exact
// weld closes the surface), triangulated along one diagonal.
#pragma once

#include <cstdint>
#include <vector>

#include "tessellation.h"

namespace sdb::gim {

// Triangles over the n x n grid, vertex y * n + x, every quad cut along the diagonal
// (x, y)-(x+1, y+1): the paper's choice, which linear subdivision carries onto the next level's
// (Section 5). Counter-clockwise in the image, so facing along T_s x T_t.
std::vector<uint32_t> grid_triangles(int n);

// SurfaceCoords (g0's quads, ptex u along image x, v along y) of the samples of level k of an
// n0 x n0 image: sample (x, y) is image point (x, y) / 2^k. k < 0 for subsampled levels.
std::vector<SurfaceCoord> grid_coords(int n0, int k);

}  // namespace sdb::gim
