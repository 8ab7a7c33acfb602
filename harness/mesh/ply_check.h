// Checks a PLY file's header against its body before OpenMesh parses it (see ply_check.cpp).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace sdb {

struct PlyLayout {
  long vertices = 0, faces = 0;
  std::vector<int> face_lines;  // ASCII only: the line of each face
};

PlyLayout check_ply(std::string_view data, const std::string& path);

}  // namespace sdb
