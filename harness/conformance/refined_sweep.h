// The corpus sweep of the uniform-refinement peers (schemes/halfedge, schemes/edgefriend: their
// levels and limit projection shared in harness/refined), on every corpus shape of a rule at
// depths 1..5 while the output stays under 400,000 triangles (depth 1 always):
//   - before projection every refined point equals Far's uniform refinement of the same mesh at
//     its ptex grid point (1e-6 of the diagonal), and every Far vertex is stood for;
//   - after it every vertex is judged against the yardstick (limit_judge.h, as the exact schemes'
//     sweeps judge theirs): its position within 1e-6 of the diagonal, its normal on its face's
//     side within `max_deg`; the vertices where the limit has no normal, where the scheme gives
//     none and those on faces with no surface are counted and printed (a shape the yardstick
//     refuses, its faces folded onto each other: positions against Far's limit masks);
//   - the output has exactly the input's boundary open (scaled by 2^depth), and no ray crack on a
//     closed input (100,000 rays, half aimed at face borders);
//   - cpu-mt's output is cpu's, bit for bit.
#pragma once

#include <functional>
#include <string>

#include "harness/core/control_mesh.h"
#include "harness/core/scheme.h"
#include "harness/core/tessellation.h"

namespace sdb::conformance {

struct RefinedPeer {
  std::string scheme;
  SubdivisionRule rule;
  // The scheme's output at `depth`: the refined level (limit false) or its projection.
  std::function<Tessellation(const ControlMesh& accepted, int depth, bool limit, Backend backend)> run;
};

// The exact schemes' bound on a normal against the limit (fragments, MiPGH).
constexpr double kExactNormalDeg = 0.01;

// Runs the sweep above with GoogleTest's EXPECTs; skips without the shared corpus.
void sweep_refined_peer(const RefinedPeer& peer, double max_deg = kExactNormalDeg);

// Every vertex of `mesh` at `depth` against the yardstick: positions within 1e-6 of the diagonal,
// normals within kExactNormalDeg, none left without one by the scheme.
void expect_limit_is_exact(const RefinedPeer& peer, const ControlMesh& mesh, int depth);

// Far's uniform refinement, vertex for vertex, on `mesh` at depths 1..4 (the built-ins' check).
void expect_refined_equals_far(const RefinedPeer& peer, const ControlMesh& mesh);

}  // namespace sdb::conformance
