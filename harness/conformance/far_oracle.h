// The exactness oracle of the recursive schemes (mesh fragments, MiPGH): OpenSubdiv's uniform
// refinement of the same mesh (Far::TopologyRefiner and PrimvarRefiner, accumulated in double),
// and the explicit vertex mapping from a scheme's output to it: every output vertex names the
// ptex grid point it stands for by its SurfaceCoord, and Far's level-d vertex at that point is
// found through uniform_vertex_coords.
#pragma once

#include <opensubdiv/far/topologyLevel.h>

#include <cstdint>
#include <functional>
#include <map>
#include <tuple>
#include <vector>

#include "harness/core/control_mesh.h"
#include "harness/core/tessellation.h"

namespace sdb::conformance {

using GridKey = std::tuple<uint32_t, int, int>;
// The ptex grid point of level `depth` a coord lies at.
GridKey grid_key(const SurfaceCoord& c, int depth);

// Far's level-d points (refined, or projected to the limit with normals) and the level-d vertex
// at each ptex grid point it has a coord for.
struct FarLevel {
  std::vector<Point3> points, normals;
  std::map<GridKey, int> at;
  std::vector<char> on_hole;  // the vertex's coord lies in a hole (no scheme output there)
  std::vector<char> faceless;
  std::vector<char> special;  // where Far's limit masks are not the exact limit (far_limit_is_exact)
  bool has_coord(size_t v) const { return !faceless[v]; }
};

// Far's limit masks (PrimvarRefiner::Limit) are exact at smooth vertices of valence 3 and more, at
// regular creases and at a boundary corner of one face, and nowhere sharpness is left.
bool far_limit_is_exact(const OpenSubdiv::Far::TopologyLevel& l, int v, SubdivisionRule rule);

FarLevel far_level(const ControlMesh& m, SubdivisionRule rule, int depth, bool limit);

double distance(const Point3& a, const Point3& b);

struct Match {
  double max_rel = 0;  // largest distance over the diagonal
  double max_deg = 0;  // largest normal angle (limit only)
  long uncovered = 0;  // Far vertices (not inside holes) no output vertex stands for
  long unmatched = 0;  // output vertices at a grid point Far has no coord for (ptex borders)
};

// Every output vertex against Far's vertex at its grid point (Far's limit masks approximate
// where `special` says: a scheme's limit is judged against the yardstick, limit_judge.h).
Match compare(const Tessellation& t, const FarLevel& far, int depth, double diagonal, bool normals);

}  // namespace sdb::conformance
