// Checks a PLY file's header against its body before OpenMesh parses it (see ply_check.cpp).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace sdb {

struct PlyLayout {
  long vertices = 0, faces = 0;
  std::vector<int> face_lines;  // ASCII only: the line of each face
  size_t body = 0;              // byte offset of the body
  bool ascii = true;
};

// The file with every line break as LF (CR and CRLF ends read alike), the header always and the
// body where it is ASCII: what OpenMesh is given, since its reader takes LF alone.
std::string with_lf_line_ends(std::string_view data, const PlyLayout& layout);

PlyLayout check_ply(std::string_view data, const std::string& path);

}  // namespace sdb
