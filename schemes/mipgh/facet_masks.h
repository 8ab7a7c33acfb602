// The normals of the nodes of D-facets next to extraordinary vertices, from level 0's control
// points: regular_patches.h's idea where no bicubic patch exists.
//
// The limit tangents of a node at level sigma are a fixed linear function of the control points
// of its D-facet's 1-ring (the faces at its corners: no refined node of the facet or along its
// sides reads anything else). Composed once in prepare, in double (OpenSubdiv's own uniform
// refinement and limit masks of the 1-ring, the rules the mesh shader applies: Sdc's), they are
// weights on those control points' differences from the facet's first corner, which float holds
// to its relative precision at every level; the per-frame work is one weighted sum per tangent.
// Facets of one 1-ring topology share their weights. Untagged interior 1-rings of quads only: a
// tagged or boundary facet keeps the level's own masks (its normals are judged as before).
#pragma once

#include <cstdint>
#include <vector>

#include "harness/core/control_mesh.h"
#include "schemes/mipgh/atlas.h"
#include "schemes/mipgh/lod.h"
#include "schemes/mipgh/shader.h"

namespace sdb::mipgh {

struct RegularPatches;

struct FacetMasks {
  // Per D-facet: -1 none, else its row in `facets`.
  std::vector<int32_t> facet;
  struct Facet {
    uint32_t type;                  // its weights: types[type]
    uint32_t first;                 // its 1-ring's control points: control[first .. first + type's size)
  };
  std::vector<Facet> facets;
  std::vector<uint32_t> control;
  struct Type {
    int size = 0;  // control points in the 1-ring
    // Per level sigma, per grid node (i, j) row-major over its n x n grid: `size` weights in T1,
    // then `size` in T2 (the corners' unused: the D-vertices' tangents are vertex_tangents.h's).
    std::vector<std::vector<float>> weights;
    // The same per level, laid out for the per-frame sums (tile::weighted_normals): by control
    // point 1 .. size - 1 (the first's difference is zero), a row of T1 weights then one of T2,
    // `pitch[sigma]` floats each, over the nodes in the order they are written: the interior
    // row-major, then sides 0 .. 3 (a = 1 .. n - 2 each).
    std::vector<std::vector<float>> by_point;
    std::vector<size_t> pitch;
  };
  std::vector<Type> types;

  bool has(int f) const { return !facet.empty() && facet[size_t(f)] >= 0; }
  // D-facet f's interior nodes' unit normals at level sigma, row-major into `out`.
  void interior_normals(int f, int sigma, const V3* base, V3* out) const;
  // The nodes a = 1 .. n - 2 of its side `side` (lod.h's side_ij), into out[a - 1].
  void side_normals(int f, int sigma, int side, const V3* base, V3* out) const;
};

// For every quad D-facet that `regular` leaves (untagged, interior, quads around), at levels
// 1 .. depth (an adaptive D-edge is projected at the finer of its D-facets' levels).
FacetMasks compose_facet_masks(const ControlMesh& mesh, const DAtlas& atlas, const EdgeTags& tags,
                               const RegularPatches& regular, int depth);

}  // namespace sdb::mipgh
