// R1 of the mesh-mutation paper for a quad/triangle scheme: every face of more than four sides
// split without new vertices into quads fanned from its first corner and, for an odd number of
// sides, a last triangle ((0 1 2 3), (0 3 4 5), ..., (0 n-2 n-1)). Quads and triangles are kept.
// The diagonals are smooth new edges; a hole's parts are holes.
#pragma once

#include "harness/core/control_mesh.h"

namespace sdb {

ControlMesh split_polygons(const ControlMesh& mesh);

}  // namespace sdb
