// One Catmull-Clark step through OpenSubdiv: turns any polygon mesh into quads with the same
// limit surface (the c-patch paper's preprocessing).
#pragma once

#include "harness/core/control_mesh.h"

namespace sdb {

ControlMesh quadrangulate(const ControlMesh& mesh);

}  // namespace sdb
