#include "harness/mesh/mesh_io.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/core/errors.h"

namespace sdb {
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::string read_text(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path, "no such file");
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, "is a directory, not a mesh file");
  // A fifo or a device would block the read forever, or never end.
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, "not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw InputError(path, "read error");
  return ss.str();
}

}  // namespace

ControlMesh read_mesh(const std::string& path) {
  const std::string ext = lower_extension(path);
  ControlMesh mesh;
  if (ext == ".obj") {
    mesh = parse_obj(read_text(path), path);
  } else if (ext == ".off") {
    const std::string data = read_text(path);
    mesh = is_binary_off(data) ? parse_binary_off(data, path) : parse_off(data, path);
  } else if (ext == ".ply") {
    mesh = read_openmesh_file(path, read_text(path));
  } else {
    throw InputError(path, "unknown mesh format '" + ext + "' (expected .obj, .off or .ply)");
  }
  mesh.name = std::filesystem::path(path).stem().string();
  return mesh;
}

namespace {
// Messages quote vertex indices as the file writes them: 1-based in OBJ, 0-based in OFF and PLY.
int file_index_base(const ControlMesh& m) { return lower_extension(m.source) == ".obj" ? 1 : 0; }
}  // namespace

void check_mesh_data(const ControlMesh& m) {
  const std::string& src = m.source;
  const int base = file_index_base(m);
  if (m.positions.empty()) throw InputError(src, "empty mesh: no vertices");
  if (m.face_sizes.empty()) throw InputError(src, "empty mesh: no faces");
  for (size_t i = 0; i < m.positions.size(); ++i)
    for (float c : m.positions[i])
      if (!std::isfinite(c)) throw InputError(src, "NaN or Inf coordinate in vertex " + std::to_string(i));
  const auto off = face_offsets(m);
  if (off.back() != static_cast<int>(m.face_vertices.size()))
    throw InputError(src, "face sizes and face-vertex list disagree");
  const int nv = num_vertices(m);
  for (int f = 0; f < num_faces(m); ++f) {
    const int n = m.face_sizes[f];
    if (n < 3)
      throw InputError(face_location(m, f), "face has " + std::to_string(n) + " vertices; at least 3 needed");
    for (int k = 0; k < n; ++k) {
      const int v = m.face_vertices[off[f] + k];
      if (v < 0 || v >= nv)
        // long: an OBJ index of 2^31 is stored as INT32_MAX and quoted 1-based (UBSan in tests/fuzz).
        throw InputError(face_location(m, f), "vertex index " + std::to_string(long(v) + base) + " out of range (mesh has " +
                                                  std::to_string(nv) + " vertices)");
    }
  }
}

void write_obj(const ControlMesh& m, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw InputError(path, "cannot write");
  out.precision(9);
  out << "# " << m.name << " (" << m.source << ")\n";
  for (const auto& p : m.positions) out << "v " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
  const auto off = face_offsets(m);
  for (int f = 0; f < num_faces(m); ++f) {
    out << 'f';
    for (int k = off[f]; k < off[f + 1]; ++k) out << ' ' << m.face_vertices[k] + 1;
    out << '\n';
  }
  for (const auto& c : m.creases) out << "t crease 2/1/0 " << c.v0 << ' ' << c.v1 << ' ' << c.sharpness << '\n';
  for (const auto& c : m.corners) out << "t corner 1/1/0 " << c.vertex << ' ' << c.sharpness << '\n';
  for (int h : m.holes) out << "t hole 1/0/0 " << h << '\n';
  if (m.boundary != BoundaryRule::EdgeOnly)
    out << "t interpolateboundary 1/0/0 " << (m.boundary == BoundaryRule::None ? 0 : 1) << '\n';
  if (m.crease_method == CreaseMethod::Chaikin) out << "t creasemethod 0/0/1 chaikin\n";
  if (m.triangle_rule == TriangleRule::Smooth) out << "t smoothtriangles 0/0/1 smooth\n";
  if (!out) throw InputError(path, "write failed");
}

}  // namespace sdb
