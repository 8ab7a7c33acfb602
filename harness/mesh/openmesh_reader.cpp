// OFF and PLY through OpenMesh's readers. OpenMesh's ImporterT repairs non-manifold input by
// duplicating vertices; we intercept faces before that happens and keep the file's data exactly,
// so non-manifold input is reported instead of silently changed.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/importer/ImporterT.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "harness/core/errors.h"
#include "harness/mesh/mesh_io.h"

namespace sdb {
namespace {

using OmMesh = OpenMesh::PolyMesh_ArrayKernelT<>;

class RawImporter : public OpenMesh::IO::ImporterT<OmMesh> {
 public:
  explicit RawImporter(OmMesh& mesh) : ImporterT<OmMesh>(mesh) {}

  OpenMesh::FaceHandle add_face(const VHandles& idx) override {
    face_sizes.push_back(static_cast<int>(idx.size()));
    for (auto vh : idx) face_vertices.push_back(vh.idx());
    return OpenMesh::FaceHandle();  // never hand the face to the half-edge kernel
  }

  std::vector<int> face_sizes, face_vertices;
};

// ASCII OFF: OpenMesh reads numbers with operator>>, which turns "1.x" into silence. This pass
// finds such tokens and maps element k to its line, so messages can name the line.
struct OffLines {
  std::string clean_text;         // the file without comments, which OpenMesh's reader does not skip
  std::vector<int> element_line;  // line of each data line after the header
  int vertex_start = 0;           // index into element_line of vertex 0
  long nv = -1, nf = -1;
};

OffLines scan_ascii_off(const std::string& path) {
  std::ifstream in(path);
  OffLines out;
  std::string line;
  int line_no = 0;
  std::vector<std::pair<int, std::string>> data;
  while (std::getline(in, line)) {
    ++line_no;
    if (auto h = line.find('#'); h != std::string::npos) line.resize(h);
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    data.emplace_back(line_no, line);
    out.clean_text += line + "\n";
  }
  if (data.empty()) throw InputError(path, "empty file");
  std::istringstream header(data[0].second);
  std::string magic;
  header >> magic;
  if (magic.find("OFF") == std::string::npos) throw InputError(at_line(path, data[0].first), "missing OFF header");
  if (magic.find("BINARY") != std::string::npos) return out;
  size_t counts_at = 1;
  std::vector<std::string> count_tok;
  for (std::string t; header >> t;) count_tok.push_back(t);
  if (count_tok.empty()) {
    if (data.size() < 2) throw InputError(path, "missing vertex and face counts");
    std::istringstream c(data[1].second);
    for (std::string t; c >> t;) count_tok.push_back(t);
    counts_at = 2;
  }
  const int count_line = data[counts_at - 1].first;
  if (count_tok.size() < 2) throw InputError(at_line(path, count_line), "expected vertex and face counts");
  for (int k = 0; k < 2; ++k) {
    long v = 0;
    auto [p, ec] = std::from_chars(count_tok[k].data(), count_tok[k].data() + count_tok[k].size(), v);
    if (ec != std::errc() || p != count_tok[k].data() + count_tok[k].size() || v < 0)
      throw InputError(at_line(path, count_line), "malformed count '" + count_tok[k] + "'");
    (k == 0 ? out.nv : out.nf) = v;
  }
  out.vertex_start = 0;
  for (size_t i = counts_at; i < data.size(); ++i) {
    out.element_line.push_back(data[i].first);
    std::istringstream ts(data[i].second);
    for (std::string t; ts >> t;) {
      float value = 0;
      auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
      if (ec != std::errc() || p != t.data() + t.size())
        throw InputError(at_line(path, data[i].first), "malformed number '" + t + "'");
      if (!std::isfinite(value)) throw InputError(at_line(path, data[i].first), "NaN or Inf coordinate");
    }
  }
  if (static_cast<long>(out.element_line.size()) < out.nv + out.nf)
    throw InputError(path, "header announces " + std::to_string(out.nv) + " vertices and " + std::to_string(out.nf) +
                               " faces, file has " + std::to_string(out.element_line.size()) + " data lines");
  return out;
}

bool is_ascii_off(const std::string& path) {
  std::ifstream in(path);
  std::string first;
  std::getline(in, first);
  return first.find("OFF") != std::string::npos && first.find("BINARY") == std::string::npos;
}

}  // namespace

ControlMesh read_openmesh_file(const std::string& path) {
  OffLines lines;
  const bool off = path.size() > 4 && (path.substr(path.size() - 4) == ".off" || path.substr(path.size() - 4) == ".OFF");
  if (off && is_ascii_off(path)) lines = scan_ascii_off(path);

  OmMesh om;
  RawImporter importer(om);
  OpenMesh::IO::Options opt;
  bool ok = false;
  if (!lines.clean_text.empty()) {
    std::istringstream text(lines.clean_text);
    ok = OpenMesh::IO::IOManager().read(text, "off", importer, opt);
  } else {
    ok = OpenMesh::IO::IOManager().read(path, importer, opt);
  }
  if (!ok) throw InputError(path, "OpenMesh could not parse the file");

  ControlMesh m;
  m.source = path;
  // Vertices go into OpenMesh's kernel unchanged (only add_face would duplicate them).
  for (const auto& vh : om.vertices()) {
    const auto& p = om.point(vh);
    m.positions.push_back({p[0], p[1], p[2]});
  }
  m.face_sizes = std::move(importer.face_sizes);
  m.face_vertices = std::move(importer.face_vertices);
  if (!lines.element_line.empty()) {
    if (static_cast<long>(m.positions.size()) != lines.nv)
      throw InputError(path, "read " + std::to_string(m.positions.size()) + " vertices, header says " +
                                 std::to_string(lines.nv));
    if (static_cast<long>(m.face_sizes.size()) != lines.nf)
      throw InputError(path, "read " + std::to_string(m.face_sizes.size()) + " faces, header says " +
                                 std::to_string(lines.nf));
    for (long f = 0; f < lines.nf; ++f) m.face_lines.push_back(lines.element_line[lines.nv + f]);
  }
  check_mesh_data(m);
  return m;
}

}  // namespace sdb
