// MiPGH, mesh mutation in programmable graphics hardware (Shiue, Goel, Peters 2003): the public
// face of the scheme folder, for its tests and tools. The harness reaches it through the registry
// (scheme.cpp) only.
#pragma once

#include <memory>

#include "harness/core/control_mesh.h"
#include "harness/core/scheme.h"
#include "schemes/mipgh/adaptive.h"

namespace sdb::mipgh {

// The mesh shader a scheme binds: Catmull-Clark (mipgh-cc), Loop (mipgh-loop), or Stam and Loop's
// quad/triangle rules (mipgh-quadtri: Catmull-Clark on quads, Loop on triangles, their blend
// where they meet; quad_tri_shader.cpp).
enum class MeshRule { CatmullClark, Loop, QuadTri };
// The rule Far refines the tags and holes with: quad/triangle meshes as Catmull-Clark's.
inline SubdivisionRule far_rule(MeshRule r) {
  return r == MeshRule::Loop ? SubdivisionRule::Loop : SubdivisionRule::CatmullClark;
}
inline MeshRule mesh_rule(SubdivisionRule r) { return r == SubdivisionRule::Loop ? MeshRule::Loop : MeshRule::CatmullClark; }

// project_to_limit = false returns the last level's refined nodes (the exactness oracle's side,
// and the paper's mutation steps alone: the `limit=0` parameter); the normals are left zero.
// mipgh-quadtri has no limit masks (none are known for its mixed vertices): project_to_limit
// must be false for it.
// A criterion other than Uniform refines adaptively (adaptive.h), on every backend.
std::unique_ptr<Evaluation> make_evaluation(const ControlMesh& mesh, MeshRule rule, const RunRequest& request,
                                            bool project_to_limit = true, AdaptiveCriterion criterion = {});
inline std::unique_ptr<Evaluation> make_evaluation(const ControlMesh& mesh, SubdivisionRule rule,
                                                   const RunRequest& request, bool project_to_limit = true,
                                                   AdaptiveCriterion criterion = {}) {
  return make_evaluation(mesh, mesh_rule(rule), request, project_to_limit, criterion);
}

}  // namespace sdb::mipgh
