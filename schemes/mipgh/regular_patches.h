// The normals of the nodes inside (and along) regular D-facets from level 0's control points.
//
// Taken at the level the limit is projected at, a node's tangents are differences of float points
// 2^-level of an edge apart whose rounding (an ulp of coordinates relative to the box's centre)
// the tangent stencils divide by that spacing: the error doubles with every level (the sword's
// normals: 0.010 degrees at depth 1, 0.024 at 2, 0.056 at 3, where mipgh's bound is 0.01). Over a
// regular D-facet (a quad whose corners are interior valence-4 D-vertices, every edge of its
// 3 x 3 quads untagged) the limit surface is the bicubic B-spline patch of its 16 control points,
// so its nodes' tangents are the patch's derivatives at their grid points: weights (per level,
// per row or column, in double once) on the control points' differences from the facet's first
// corner, which float holds to its relative precision at any level. Positions stay the stencils'
// (their rounding is absolute, 1e-7 of the diagonal at any depth). The D-vertices' tangents come
// from vertex_tangents.h the same way.
#pragma once

#include <cstdint>
#include <vector>

#include "schemes/mipgh/atlas.h"
#include "schemes/mipgh/lod.h"
#include "schemes/mipgh/shader.h"

namespace sdb::mipgh {

struct RegularPatches {
  // Per D-facet: -1 where not regular, else its patch's row in `net`.
  std::vector<int32_t> patch;
  // 16 input vertices per regular D-facet, row-major over (row i, column j) = -1 .. 2 of the
  // facet's level-0 grid (corner 0 at (0, 0), corner 1 at (0, 1), corner 3 at (1, 0)).
  std::vector<uint32_t> net;
  // Per level: the cubic B-spline basis and its derivative at the level's grid points t = k / (n - 1),
  // 4 values each, k = 0 .. n - 1.
  std::vector<std::vector<float>> basis, derivative;
  // The same by function: B_m at k in [m * n + k], B'_m in [(4 + m) * n + k] (rows of SIMD lanes).
  std::vector<std::vector<float>> by_function;
  bool regular(int f) const { return !patch.empty() && patch[size_t(f)] >= 0; }
  // The limit positions (relative to `origin`, as the levels' nodes are) and unit normals (u along
  // a row, v across: the stencils' T1 x T2) of regular D-facet f's interior (rows and columns 1 ..
  // n - 2 of level sigma) from level 0's points `base`, into three planes each, node (i, j) at
  // (i - 1)(n - 2) + j - 1, as the level stores a quad's interior (tile::assemble_limit_run; the
  // planes have room for (n - 2)^2 + 1 floats: the last row's vectors run one node past). The
  // positions too: the patch is the limit surface there, so the facet's level-sigma nodes need
  // not be gathered for its interior.
  void interior_limit(int f, int sigma, const V3* base, V3 origin, float* px, float* py, float* pz, float* nx,
                      float* ny, float* nz) const;
  // The same at the points (i, j) of side `side` (a = 1 .. n - 2 from corner `side`, lod.h's
  // side_ij), written to position[a - 1] (moved by *offset where given, as the projection's) and
  // normal[a - 1]. The patch is the limit along its sides too: a D-edge with a regular D-facet on
  // either side takes its nodes from it, and the stencils need not gather its strip.
  void side_limit(int f, int sigma, int side, const V3* base, V3 origin, const V3* offset, V3* position,
                  V3* normal) const;
  // The same tangents as weights on a net's 16 points, per grid node (i, j) of level sigma
  // row-major: 16 in T1, then 16 in T2 (facet_masks.h's layout, for the Vulkan pass).
  static std::vector<float> node_weights(int sigma);
};

// The regular D-facets of a quad mesh and the bases up to level `depth`; none where `tags` has
// sharp edges or vertices around them.
RegularPatches find_regular_patches(const DAtlas& atlas, const EdgeTags& tags, int depth);

}  // namespace sdb::mipgh
