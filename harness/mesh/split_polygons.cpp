#include "harness/mesh/split_polygons.h"

#include <algorithm>

namespace sdb {

ControlMesh split_polygons(const ControlMesh& mesh) {
  ControlMesh out = mesh;
  out.face_sizes.clear(), out.face_vertices.clear(), out.face_lines.clear(), out.holes.clear();
  std::vector<char> hole(mesh.face_sizes.size(), 0);
  for (int h : mesh.holes) hole[h] = 1;
  const std::vector<int> offsets = face_offsets(mesh);
  for (int f = 0; f < num_faces(mesh); ++f) {
    const int* v = mesh.face_vertices.data() + offsets[f];
    const int n = mesh.face_sizes[f];
    auto add = [&](std::initializer_list<int> corners) {
      if (hole[f]) out.holes.push_back(num_faces(out));
      if (!mesh.face_lines.empty()) out.face_lines.push_back(mesh.face_lines[f]);
      out.face_sizes.push_back(int(corners.size()));
      for (int k : corners) out.face_vertices.push_back(v[k]);
    };
    if (n <= 4) {
      if (hole[f]) out.holes.push_back(num_faces(out));
      if (!mesh.face_lines.empty()) out.face_lines.push_back(mesh.face_lines[f]);
      out.face_sizes.push_back(n);
      out.face_vertices.insert(out.face_vertices.end(), v, v + n);
      continue;
    }
    int k = 1;
    for (; k + 2 < n; k += 2) add({0, k, k + 1, k + 2});
    if (k + 1 < n) add({0, k, k + 1});
  }
  return out;
}

}  // namespace sdb
