// The exact limit at a vertex of a refinement level, one normal per side: the yardstick at a
// base vertex, the oracle at a grid point, and the recursive schemes' limit where a semi-sharp
// feature outlasts their depth.
//
// A vertex's limit depends on its 1-ring alone, and so does its ring one level down: the child's
// faces are children of the vertex's faces, and Sdc's rules for them (Chaikin's sharpness
// included) read nothing beyond. So the faces around the vertex, refined by Far one level at a
// time and cut back to the child's faces each time, reach any depth at the cost of a ring. Once
// no semi-sharp edge or corner is left at the vertex its rules repeat from level to level, and
// the limit is exact: Far's masks (in double) where they are the limit (a smooth vertex of
// valence 3 or more; a crease's or corner's position), the eigenvectors of the ring's subdivision
// matrix elsewhere (ring_limit.h: darts, valence 2, creases, corners and boundaries, per side).
#pragma once

#include <opensubdiv/far/topologyLevel.h>
#include <opensubdiv/sdc/options.h>

#include <array>
#include <vector>

#include "harness/core/control_mesh.h"

namespace sdb {

using Point3d = std::array<double, 3>;

struct VertexLimit {
  Point3d position{};
  // Per face of the vertex, in the level's GetVertexFaces order: the unit normal on that face's
  // side, oriented as the face; zero where the surface has none there (a degenerate corner).
  std::vector<Point3d> normal;
  int levels = 0;  // refined this far below the given level before the rules repeated
};

// v of `level`, whose points (double, one per vertex of the level) are `points`. `extra_levels`
// refines that much further after the rules repeat (the tests' oracle: Far's masks deeper).
// Sharpness decays by at least one a level, so at most 10 levels are refined for it.
VertexLimit vertex_limit(const OpenSubdiv::Far::TopologyLevel& level, const OpenSubdiv::Sdc::Options& options,
                         SubdivisionRule rule, const std::vector<Point3d>& points, int v, int extra_levels = 0);

// Whether v's rules at `level` still change from level to level (a semi-sharp edge or corner at v).
bool vertex_sharpness_decays(const OpenSubdiv::Far::TopologyLevel& level, int v);

}  // namespace sdb
