// ControlMesh -> OpenSubdiv Far::TopologyRefiner, honouring creases, corners, holes and the
// boundary rule. Shared by quadrangulation and the reference surfaces.
#pragma once

#include <opensubdiv/far/topologyRefiner.h>

#include <memory>
#include <optional>
#include <string>

#include "harness/core/control_mesh.h"

namespace sdb {

// A point as Far::PrimvarRefiner interpolates it (Clear, AddWithWeight): float as the refiners
// and peers use it, double for the tests' oracles.
template <class Real>
struct PrimvarPointT {
  Real p[3];
  void Clear(void* = nullptr) { p[0] = p[1] = p[2] = Real(0); }
  void AddWithWeight(const PrimvarPointT& src, float w) {
    p[0] += w * src.p[0];
    p[1] += w * src.p[1];
    p[2] += w * src.p[2];
  }
};
using PrimvarPoint = PrimvarPointT<float>;

OpenSubdiv::Sdc::Options sdc_options(const ControlMesh& mesh);

// Throws InputError with OpenSubdiv's own message when it refuses the topology.
std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> make_refiner(const ControlMesh& mesh, SubdivisionRule rule);

// Whether Far's limit tangent masks (Sdc's ComputeVertexLimitMask, PrimvarRefiner::Limit) are
// the exact limit at vertex v: a smooth vertex of valence 3 or more, a crease with the regular
// number of faces on each side (Catmull-Clark 2, Loop 3; at a boundary, that many in all), a
// boundary corner of one face. Elsewhere (darts, valence 2, cone points, creases and corners of
// other valences) they approximate it. Sharpness decides the rule: every sharp edge counts on a
// level where it no longer decays; `infinite_only` counts only infinitely sharp edges and corners
// (a base level whose semi-sharpness refinement will spend).
bool far_tangent_masks_exact(const OpenSubdiv::Far::TopologyLevel& level, int v, SubdivisionRule rule,
                             bool infinite_only = false);

// The refiner's level `level` as a ControlMesh (creases, corners and holes carried over), with
// positions interpolated by PrimvarRefiner. The refiner must have been refined uniformly to it.
ControlMesh refined_level(const OpenSubdiv::Far::TopologyRefiner& refiner, const ControlMesh& base, int level);

// The level to take limit masks at for output at `depth`: deep enough that no semi-sharp crease
// or corner is left (Far's masks take any sharpness left as infinite, and a limit projected
// there is not the limit: 6.1e-3 of the diagonal and 87 degrees on catmark_cube_creases1 at
// depth 1 from 3 levels deeper). Sharpness s decays by at least one a level (Chaikin's too), so
// ceil(s) levels spend it. Recursive schemes refine this far and sample `depth`'s grid.
int limit_depth_for(const ControlMesh& mesh, int depth);

// Where refining `faces` faces to limit_depth_for would pass `budget` faces at that level, the
// refusal a recursive scheme gives up front (its tables or levels would not fit), naming the
// sharpness that asks for it; nothing otherwise.
std::optional<std::string> limit_depth_refusal(const ControlMesh& mesh, int depth, double faces, double budget);

}  // namespace sdb
