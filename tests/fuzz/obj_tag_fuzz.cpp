// OpenSubdiv `t` tag lines of the OBJ reader: every input line becomes a tag line of a fixed
// cube, so that mutations land in the tag parser (counts, integers, floats, strings) and in the
// checks of what a tag names (edges, vertices, faces), not in the vertex and face lines.
#include <string>

#include "harness/mesh/mesh_io.h"
#include "tests/fuzz/contract.h"

namespace {

constexpr const char* kCube =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

std::string cube_with_tags(std::string_view tags) {
  std::string text = kCube;
  size_t pos = 0;
  while (pos <= tags.size()) {
    size_t end = tags.find('\n', pos);
    if (end == std::string_view::npos) end = tags.size();
    text += "t ";
    text += tags.substr(pos, end - pos);
    text += '\n';
    pos = end + 1;
  }
  return text;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = "fuzz-tags.obj";
  const std::string text = cube_with_tags(sdb::fuzz::as_text(data, size));
  sdb::fuzz::holds_contract(path, [&] {
    const sdb::ControlMesh m = sdb::parse_obj(text, path);
    sdb::fuzz::require_valid_mesh(m);
    sdb::fuzz::require(m.positions.size() == 8 && m.face_sizes.size() == 6, "tags changed the cube's vertices or faces");
  });
  return 0;
}
