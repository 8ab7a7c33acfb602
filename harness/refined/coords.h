// Where each vertex of a corner-split level lies on the base mesh (its SurfaceCoord) and the
// level's triangles, without OpenSubdiv: every face's corners are followed through the splits in
// ptex space, in integer units of 2^-depth, exactly as harness/reference/uniform_coords.cpp
// follows Far's (a child's corner is its parent's corner, the middle of one of its edges, or its
// centre; an n-gon's first Catmull-Clark children are its ptex sub-faces).
//
// The split this module knows: child face `face_size * f + i` of face f is the one at its corner
// i, its corners (the corner, the middle of the edge to corner i + 1, [the face's centre,] the
// middle of the edge from corner i - 1); under Loop, child 3F + f is the middle triangle, its
// corner j the middle of the edge from corner j - 1 to j. Dupuy and Vanhoey's halfedge
// refinement and Edge-Friend number their children so.
#pragma once

#include <cstdint>
#include <vector>

#include "harness/core/control_mesh.h"
#include "harness/core/tessellation.h"

namespace sdb::refined {

struct CornerCoord {
  uint32_t face = 0;  // ptex face
  uint32_t u = 0, v = 0;
};

// Corner coords of every face of a level, in corner order, in units of 2^-scale.
struct LevelCorners {
  int scale = 0;
  std::vector<CornerCoord> corners;
};

// The first level whose faces all have the same size: a Loop mesh's triangles (level 0), a
// Catmull-Clark mesh of quads (level 0), or of other faces: its first refinement, the children
// of base corner c (in face-vertex order) being face c (level 1). Ptex faces numbered as
// Far::PtexIndices numbers them (one per quad or Loop triangle, one per corner of other faces).
LevelCorners first_uniform_corners(const ControlMesh& mesh, SubdivisionRule rule);

// One corner split of every face (face size 4 or 3, `faces` of them).
LevelCorners split_corners(const LevelCorners& parent, uint32_t face_size);

// A SurfaceCoord for every vertex (from the first face corner at it), given the level's vertex of
// each corner.
std::vector<SurfaceCoord> vertex_coords(const LevelCorners& level, const uint32_t* verts, uint32_t num_vertices);

// Two triangles per quad (corners 0 1 2 and 0 2 3) or the triangle itself.
std::vector<uint32_t> level_triangles(const uint32_t* verts, uint64_t corners, uint32_t face_size);

}  // namespace sdb::refined
