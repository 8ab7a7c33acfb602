// What the fragments' sweeps share: the shapes they run and the open edges an output must have.
#pragma once

#include <string>
#include <vector>

#include "harness/core/control_mesh.h"

namespace sdb::fragments::testing {

// The corpus shapes of a rule (OpenSubdiv's regression shapes) and the real meshes issue 12 names,
// those present in ../shared.
std::vector<std::string> sweep_shapes(SubdivisionRule rule);

// A sweep shape loaded, taken by OpenSubdiv and accepted as the rule's fragments scheme takes it
// (quadrangulated for Catmull-Clark); throws InputError, naming why, where it is refused.
ControlMesh sweep_mesh(const std::string& name, SubdivisionRule rule);

// Edges of exactly one face with a surface: the borders of holes count.
long boundary_edges(const ControlMesh& m);

}  // namespace sdb::fragments::testing
