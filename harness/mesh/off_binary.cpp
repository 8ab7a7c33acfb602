// Binary OFF as OpenMesh writes it (IO::Options::Binary): the line "OFF BINARY", then little-endian
// int32 vertex, face and edge counts, three float32 per vertex, and per face an int32 size followed
// by that many int32 indices. Read here rather than by OpenMesh, whose reader reserves memory for
// whatever counts the header announces (a 30-byte file asked for 16 GB; found by tests/fuzz) and
// reads past the end of a short file; here every count is held to the bytes the file has.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "harness/core/errors.h"
#include "harness/mesh/mesh_io.h"
#include "harness/mesh/text_lines.h"

namespace sdb {
namespace {

static_assert(std::endian::native == std::endian::little, "binary OFF is read as little-endian words");

struct LittleEndianWords {
  std::string_view data;
  size_t pos;

  size_t remaining() const { return data.size() - pos; }
  template <class T>
  bool read(T& out) {
    static_assert(sizeof(T) == 4);
    if (remaining() < 4) return false;
    std::memcpy(&out, data.data() + pos, 4);
    pos += 4;
    return true;
  }
};

struct Counts {
  int32_t vertices = 0, faces = 0, edges = 0;
};

Counts read_counts(LittleEndianWords& in, const std::string& path) {
  Counts c;
  if (!in.read(c.vertices) || !in.read(c.faces) || !in.read(c.edges))
    throw InputError(path, "file ends inside the vertex, face and edge counts");
  if (c.vertices < 0 || c.faces < 0)
    throw InputError(path, "negative count in the header (" + std::to_string(c.vertices) + " vertices, " +
                               std::to_string(c.faces) + " faces)");
  // A vertex takes 12 bytes and a face at least 16 (its size and three indices).
  if (uint64_t(c.vertices) * 12 + uint64_t(c.faces) * 16 > in.remaining())
    throw InputError(path, "header announces " + std::to_string(c.vertices) + " vertices and " + std::to_string(c.faces) +
                               " faces, more than the file's " + std::to_string(in.remaining()) + " bytes after it hold");
  return c;
}

void read_vertices(LittleEndianWords& in, const Counts& c, ControlMesh& m, const std::string& path) {
  m.positions.resize(c.vertices);
  for (int32_t v = 0; v < c.vertices; ++v)
    for (float& x : m.positions[v]) {
      in.read(x);  // the counts check guarantees the bytes
      if (!std::isfinite(x)) throw InputError(path, "NaN or Inf coordinate in vertex " + std::to_string(v));
    }
}

void read_faces(LittleEndianWords& in, const Counts& c, ControlMesh& m, const std::string& path) {
  for (int32_t f = 0; f < c.faces; ++f) {
    const std::string face = "face " + std::to_string(f);
    int32_t n = 0;
    if (!in.read(n)) throw InputError(path, "file ends before " + face + " of the " + std::to_string(c.faces) + " announced");
    if (n < 3) throw InputError(path, face + " has " + std::to_string(n) + " vertices; at least 3 needed");
    if (uint64_t(n) * 4 > in.remaining())
      throw InputError(path, "file ends inside " + face + ", which announces " + std::to_string(n) + " vertices");
    for (int32_t k = 0; k < n; ++k) {
      int32_t v = 0;
      in.read(v);
      if (v < 0 || v >= c.vertices)
        throw InputError(path, face + ": vertex index " + std::to_string(v) + " out of range (mesh has " +
                                   std::to_string(c.vertices) + " vertices)");
      m.face_vertices.push_back(v);
    }
    m.face_sizes.push_back(n);
  }
}

}  // namespace

bool is_binary_off(std::string_view text) {
  const auto head = text::tokens(text.substr(0, text.find('\n')));
  return head.size() >= 2 && head[0].ends_with("OFF") && head[1] == "BINARY";
}

ControlMesh parse_binary_off(std::string_view data, const std::string& path) {
  const size_t eol = data.find('\n');
  const auto head = text::tokens(data.substr(0, eol));
  if (head.size() != 2 || head[0] != "OFF")
    throw InputError(at_line(path, 1), "only plain 'OFF BINARY' is read in binary (no colours, normals or other dimensions)");
  LittleEndianWords in{data, eol + 1};
  const Counts counts = read_counts(in, path);
  ControlMesh m;
  m.source = path;
  read_vertices(in, counts, m, path);
  read_faces(in, counts, m, path);
  // A trailing newline or two is a writer's habit; more is data the header does not announce.
  if (in.remaining() > 2)
    throw InputError(path, std::to_string(in.remaining()) + " bytes after the last face the header announces");
  check_mesh_data(m);
  return m;
}

}  // namespace sdb
