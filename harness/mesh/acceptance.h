// Whether a mesh is one a scheme accepts (SchemeInfo::accepts), and the mesh to hand it.
#pragma once

#include "harness/core/control_mesh.h"
#include "harness/core/scheme.h"
#include "harness/mesh/facts.h"

namespace sdb {

// Checks a mesh against a scheme's requirements: returns the mesh to hand to prepare() (quadrangulated
// when the scheme asks for quads and allows it) or throws InputError saying why the scheme refuses it.
ControlMesh accept_mesh(const ControlMesh& mesh, const SchemeInfo& info);
// The same with the mesh's facts (compute_facts) given: a run's mesh is offered to every scheme,
// and the caller computes its facts once (MeasureContext::facts).
ControlMesh accept_mesh(const ControlMesh& mesh, const SchemeInfo& info, const MeshFacts& facts);

}  // namespace sdb
