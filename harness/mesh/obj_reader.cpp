// OBJ with OpenSubdiv's tag lines:  t <name> <nint>/<nfloat>/<nstring> ints... floats... strings...
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "harness/core/errors.h"
#include "harness/mesh/mesh_io.h"
#include "harness/mesh/text_lines.h"

namespace sdb {
namespace {

using text::LineParser;
using text::quoted;
using text::tokens;
using text::trim;

struct PendingCrease {
  EdgeCrease crease;
  int line;
};

struct ObjState {
  ControlMesh mesh;
  std::vector<PendingCrease> creases;
  std::vector<std::pair<int, int>> corner_lines, hole_lines;  // (index into mesh vector, line)
};

void parse_vertex(const LineParser& p, const std::vector<std::string_view>& tok, ObjState& s) {
  // v x y z [w] or v x y z r g b (vertex colours): only x y z matter.
  if (tok.size() < 4) p.fail("vertex needs 3 coordinates, found " + std::to_string(tok.size() - 1));
  Point3 pt{p.number(tok[1]), p.number(tok[2]), p.number(tok[3])};
  for (size_t i = 4; i < tok.size(); ++i) p.number(tok[i]);
  for (float c : pt)
    if (!std::isfinite(c)) p.fail("NaN or Inf coordinate in vertex " + std::to_string(s.mesh.positions.size() + 1));
  s.mesh.positions.push_back(pt);
}

void parse_face(const LineParser& p, const std::vector<std::string_view>& tok, ObjState& s, int line) {
  if (tok.size() < 4) p.fail("face has " + std::to_string(tok.size() - 1) + " vertices; at least 3 needed");
  const long count = static_cast<long>(s.mesh.positions.size());
  for (size_t i = 1; i < tok.size(); ++i) {
    std::string_view t = tok[i];
    const size_t slash = t.find('/');
    std::string_view vpart = t.substr(0, slash);
    if (slash != std::string_view::npos) {  // v/vt/vn: texture and normal indices are checked for syntax only
      std::string_view rest = t.substr(slash + 1);
      for (size_t k = 0; k <= rest.size();) {
        size_t e = rest.find('/', k);
        if (e == std::string_view::npos) e = rest.size();
        if (e > k) p.integer(rest.substr(k, e - k));
        k = e + 1;
      }
    }
    long idx = p.integer(vpart);
    if (idx == 0) p.fail("vertex index 0 (OBJ indices start at 1)");
    if (idx < 0) {
      if (idx < -count) p.fail("relative index " + quoted(vpart) + " reaches before the first vertex");
      idx = count + idx;
    } else {
      idx -= 1;  // range against the final vertex count is checked after the whole file is read
    }
    if (idx > INT32_MAX) p.fail("vertex index " + quoted(vpart) + " out of range");
    s.mesh.face_vertices.push_back(static_cast<int>(idx));
  }
  s.mesh.face_sizes.push_back(static_cast<int>(tok.size() - 1));
  s.mesh.face_lines.push_back(line);
}

struct Tag {
  std::string_view name;
  std::vector<long> ints;
  std::vector<float> floats;
  std::vector<std::string_view> strings;
};

Tag parse_tag(const LineParser& p, const std::vector<std::string_view>& tok) {
  if (tok.size() < 3) p.fail("tag needs a name and <nint>/<nfloat>/<nstring>");
  Tag tag{tok[1], {}, {}, {}};
  long n[3] = {0, 0, 0};
  std::string_view c = tok[2];
  const long given = static_cast<long>(tok.size()) - 3;
  for (int k = 0; k < 3; ++k) {
    size_t e = c.find('/');
    if ((k < 2) == (e == std::string_view::npos)) p.fail("malformed tag counts " + quoted(tok[2]));
    n[k] = p.integer(c.substr(0, e));
    if (n[k] < 0) p.fail("negative tag count " + quoted(tok[2]));
    // Each count checked alone first, so that their sum cannot overflow.
    if (n[k] > given)
      p.fail("tag '" + std::string(tag.name) + "' announces " + quoted(tok[2]) + " arguments, has " + std::to_string(given));
    c = k < 2 ? c.substr(e + 1) : c;
  }
  if (given != n[0] + n[1] + n[2])
    p.fail("tag '" + std::string(tag.name) + "' announces " + std::to_string(n[0] + n[1] + n[2]) +
           " arguments, has " + std::to_string(given));
  size_t i = 3;
  for (long k = 0; k < n[0]; ++k) tag.ints.push_back(p.integer(tok[i++]));
  for (long k = 0; k < n[1]; ++k) {
    float f = p.number(tok[i++]);
    if (!std::isfinite(f)) p.fail("NaN or Inf in tag '" + std::string(tag.name) + "'");
    tag.floats.push_back(f);
  }
  for (long k = 0; k < n[2]; ++k) tag.strings.push_back(tok[i++]);
  return tag;
}

float tag_float(const LineParser& p, const Tag& t, size_t i) {
  if (t.floats.empty()) p.fail("tag '" + std::string(t.name) + "' needs a sharpness value");
  return std::max(0.0f, t.floats.size() > 1 ? t.floats.at(std::min(i, t.floats.size() - 1)) : t.floats[0]);
}

int tag_index(const LineParser& p, const Tag& t, size_t i, const char* what) {
  const long v = t.ints[i];
  if (v < 0 || v > INT32_MAX)
    p.fail("tag '" + std::string(t.name) + "' names " + what + " " + std::to_string(v) + ", out of range");
  return static_cast<int>(v);
}

void apply_tag(const LineParser& p, const Tag& t, ObjState& s, int line) {
  ControlMesh& m = s.mesh;
  if (t.name == "crease") {
    if (t.ints.size() < 2 || t.ints.size() % 2) p.fail("crease tag needs vertex pairs");
    for (size_t j = 0; j + 1 < t.ints.size(); j += 2)
      s.creases.push_back({{tag_index(p, t, j, "vertex"), tag_index(p, t, j + 1, "vertex"), tag_float(p, t, j / 2)}, line});
  } else if (t.name == "corner") {
    for (size_t j = 0; j < t.ints.size(); ++j) {
      s.corner_lines.emplace_back(static_cast<int>(m.corners.size()), line);
      m.corners.push_back({tag_index(p, t, j, "vertex"), tag_float(p, t, j)});
    }
  } else if (t.name == "hole") {
    for (size_t j = 0; j < t.ints.size(); ++j) {
      s.hole_lines.emplace_back(static_cast<int>(m.holes.size()), line);
      m.holes.push_back(tag_index(p, t, j, "face"));
    }
  } else if (t.name == "interpolateboundary") {
    // Numbering as OpenSubdiv's regression shapes: 0 none, 1 edge-and-corner, 2 edge-only.
    if (t.ints.size() != 1) p.fail("interpolateboundary takes one integer");
    switch (t.ints[0]) {
      case 0: m.boundary = BoundaryRule::None; break;
      case 1: m.boundary = BoundaryRule::EdgeAndCorner; break;
      case 2: m.boundary = BoundaryRule::EdgeOnly; break;
      default: p.fail("unknown interpolateboundary rule " + std::to_string(t.ints[0]));
    }
  } else if (t.name == "creasemethod") {
    if (t.strings.size() != 1) p.fail("creasemethod takes one string");
    if (t.strings[0] == "chaikin") m.crease_method = CreaseMethod::Chaikin;
    else if (t.strings[0] == "normal") m.crease_method = CreaseMethod::Uniform;
    else p.fail("unknown creasemethod '" + std::string(t.strings[0]) + "'");
  } else if (t.name == "smoothtriangles") {
    if (t.strings.size() != 1) p.fail("smoothtriangles takes one string");
    if (t.strings[0] == "smooth") m.triangle_rule = TriangleRule::Smooth;
    else if (t.strings[0] == "catmark") m.triangle_rule = TriangleRule::Catmark;
    else p.fail("unknown smoothtriangles rule '" + std::string(t.strings[0]) + "'");
  } else {
    // Hierarchical edits and face-varying options do not change the vertex limit surface that
    // OpenSubdiv 3 evaluates (it has no hierarchical edits at all); say so rather than fail.
    m.warnings.push_back(at_line(m.source, line) + ": tag '" + std::string(t.name) + "' ignored");
  }
}

// A tag given twice for one edge, vertex or face is one tag, as OpenSubdiv reads it: the last
// sharpness holds (Far sets it once per tag, in order). Kept twice, it was counted as two creased
// edges or two holes, and handed twice to Embree. Each repeat is said (file and line).
void merge_repeated_tags(ObjState& s) {
  ControlMesh& m = s.mesh;
  auto edge = [](const EdgeCrease& c) { return (uint64_t(uint32_t(std::min(c.v0, c.v1))) << 32) | uint32_t(std::max(c.v0, c.v1)); };
  std::unordered_map<uint64_t, size_t> crease_at;
  std::vector<EdgeCrease> creases;
  for (size_t i = 0; i < m.creases.size(); ++i) {
    auto [it, first] = crease_at.try_emplace(edge(m.creases[i]), creases.size());
    if (first) {
      creases.push_back(m.creases[i]);
      continue;
    }
    creases[it->second].sharpness = m.creases[i].sharpness;
    m.warnings.push_back(at_line(m.source, s.creases[i].line) + ": crease on edge (" + std::to_string(m.creases[i].v0) + "," +
                         std::to_string(m.creases[i].v1) + ") given again: one crease, the last sharpness holds");
  }
  m.creases = std::move(creases);
  std::unordered_map<int, size_t> corner_at;
  std::vector<VertexCorner> corners;
  for (const auto& [i, line] : s.corner_lines) {
    auto [it, first] = corner_at.try_emplace(m.corners[i].vertex, corners.size());
    if (first) {
      corners.push_back(m.corners[i]);
      continue;
    }
    corners[it->second].sharpness = m.corners[i].sharpness;
    m.warnings.push_back(at_line(m.source, line) + ": corner on vertex " + std::to_string(m.corners[i].vertex) +
                         " given again: one corner, the last sharpness holds");
  }
  m.corners = std::move(corners);
  std::unordered_set<int> seen;
  std::vector<int> holes;
  for (const auto& [i, line] : s.hole_lines) {
    if (seen.insert(m.holes[i]).second) holes.push_back(m.holes[i]);
    else m.warnings.push_back(at_line(m.source, line) + ": hole on face " + std::to_string(m.holes[i]) + " given again: one hole");
  }
  m.holes = std::move(holes);
}

}  // namespace

ControlMesh parse_obj(std::string_view text, const std::string& path) {
  ObjState s;
  s.mesh.source = path;
  int line_no = 0;
  size_t pos = text::after_bom(text);
  while (pos < text.size()) {
    const auto [raw, next] = text::next_line(text, pos);
    const std::string_view line = trim(raw);
    pos = next;
    ++line_no;
    if (line.empty() || line.front() == '#') continue;
    if (line.find('\0') != std::string_view::npos)
      throw InputError(at_line(path, line_no), "binary data in a text OBJ file");
    const auto tok = tokens(line);
    const std::string_view key = tok[0];
    LineParser p(path, line_no);
    if (key == "v") parse_vertex(p, tok, s);
    else if (key == "f") parse_face(p, tok, s, line_no);
    else if (key == "t") apply_tag(p, parse_tag(p, tok), s, line_no);
    // vt, vn, g, o, s, usemtl, mtllib, l, p: no bearing on the control mesh.
  }
  ControlMesh& m = s.mesh;
  if (m.positions.empty()) throw InputError(path, "empty mesh: no vertices");
  if (m.face_sizes.empty()) throw InputError(path, "empty mesh: no faces");
  for (const auto& [i, line] : s.corner_lines)
    if (m.corners[i].vertex < 0 || m.corners[i].vertex >= num_vertices(m))
      throw InputError(at_line(path, line), "corner tag names vertex " + std::to_string(m.corners[i].vertex) +
                                                ", mesh has " + std::to_string(num_vertices(m)));
  for (const auto& [i, line] : s.hole_lines)
    if (m.holes[i] < 0 || m.holes[i] >= num_faces(m))
      throw InputError(at_line(path, line), "hole tag names face " + std::to_string(m.holes[i]) +
                                                ", mesh has " + std::to_string(num_faces(m)));
  check_mesh_data(m);
  // Crease tags must name edges of the mesh (OpenSubdiv refuses the shape otherwise).
  std::unordered_set<uint64_t> edges;
  auto key = [](int a, int b) { return (uint64_t(std::min(a, b)) << 32) | uint32_t(std::max(a, b)); };
  const auto off = face_offsets(m);
  for (int f = 0; f < num_faces(m); ++f)
    for (int k = 0; k < m.face_sizes[f]; ++k)
      edges.insert(key(m.face_vertices[off[f] + k], m.face_vertices[off[f] + (k + 1) % m.face_sizes[f]]));
  for (const auto& c : s.creases) {
    if (!edges.count(key(c.crease.v0, c.crease.v1)))
      throw InputError(at_line(path, c.line), "crease tag names (" + std::to_string(c.crease.v0) + "," +
                                                  std::to_string(c.crease.v1) + "), which is not an edge");
    m.creases.push_back(c.crease);
  }
  merge_repeated_tags(s);
  return m;
}

}  // namespace sdb
