// Reading meshes: OBJ and OFF (own parsers, for OpenSubdiv's `t` tags, header counts held to the
// content, and exact line numbers) and PLY (OpenMesh's parser, the file checked against its header
// first, imported raw so that nothing is repaired behind the user's back).
// Every reader throws InputError("path:line", reason) on bad input and never returns a partial mesh.
#pragma once

#include <string>
#include <string_view>

#include "harness/core/control_mesh.h"

namespace sdb {

ControlMesh read_mesh(const std::string& path);

ControlMesh parse_obj(std::string_view text, const std::string& path);
// Whether the first line is "<prefix>OFF BINARY" (parse_binary_off reads plain "OFF BINARY" only).
bool is_binary_off(std::string_view text);
ControlMesh parse_off(std::string_view text, const std::string& path);  // ASCII OFF
ControlMesh parse_binary_off(std::string_view data, const std::string& path);
// PLY (`data`: the file's bytes, for the checks made before OpenMesh reads it).
ControlMesh read_openmesh_file(const std::string& path, std::string_view data);

// Checks every reader ends with: counts, index ranges, face sizes, finite coordinates.
// Repeated vertices in a face and non-manifold edges are not errors here: OpenSubdiv's own
// regression shapes use them on purpose; facts report them and schemes that cannot take them
// refuse the mesh (require_manifold).
void check_mesh_data(const ControlMesh& mesh);

void write_obj(const ControlMesh& mesh, const std::string& path);

}  // namespace sdb
