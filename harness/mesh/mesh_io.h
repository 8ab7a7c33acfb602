// Reading meshes: OBJ (own parser, for OpenSubdiv's `t` tags and exact line numbers), OFF and PLY
// (OpenMesh's parsers, imported raw so that nothing is repaired behind the user's back).
// Every reader throws InputError("path:line", reason) on bad input and never returns a partial mesh.
#pragma once

#include <string>
#include <string_view>

#include "harness/core/control_mesh.h"

namespace sdb {

ControlMesh read_mesh(const std::string& path);

ControlMesh parse_obj(std::string_view text, const std::string& path);
ControlMesh read_openmesh_file(const std::string& path);  // .off, .ply

// Checks every reader ends with: counts, index ranges, face sizes, finite coordinates.
// Repeated vertices in a face and non-manifold edges are not errors here: OpenSubdiv's own
// regression shapes use them on purpose; facts report them and schemes that cannot take them
// refuse the mesh (require_manifold).
void check_mesh_data(const ControlMesh& mesh);

void write_obj(const ControlMesh& mesh, const std::string& path);

}  // namespace sdb
