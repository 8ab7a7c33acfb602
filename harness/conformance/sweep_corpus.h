// The corpus sweep of the recursive schemes (issue 12's list, shared by mesh fragments and MiPGH):
// OpenSubdiv's regression shapes of a rule and the real meshes named beside them.
#pragma once

#include <string>
#include <vector>

#include "harness/core/control_mesh.h"

namespace sdb::conformance {

// The shapes present in ../shared: every opensubdiv/catmark_* (or loop_*) corpus mesh, then Spot,
// Blub, Fandisk and the sword (Loop: the bunny, Spot's triangles, the subdivided icosahedron).
std::vector<std::string> sweep_shapes(SubdivisionRule rule);

// A sweep shape loaded, taken by OpenSubdiv and accepted as `scheme` takes it (quadrangulated
// where it asks); throws InputError, naming why, where it is refused.
ControlMesh sweep_mesh(const std::string& name, SubdivisionRule rule, const std::string& scheme);

// Edges of exactly one face with a surface: the borders of holes count.
long boundary_edges(const ControlMesh& m);

}  // namespace sdb::conformance
