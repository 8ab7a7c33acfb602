// Whether a mesh is one a scheme accepts (SchemeInfo::accepts), and the mesh to hand it.
#pragma once

#include "harness/core/control_mesh.h"
#include "harness/core/scheme.h"

namespace sdb {

// Checks a mesh against a scheme's requirements: returns the mesh to hand to prepare() (quadrangulated
// when the scheme asks for quads and allows it) or throws InputError saying why the scheme refuses it.
ControlMesh accept_mesh(const ControlMesh& mesh, const SchemeInfo& info);

}  // namespace sdb
