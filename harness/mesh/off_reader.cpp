// ASCII OFF, read here rather than by OpenMesh: its reader takes a face's indices from whatever
// lines follow (a line `9 3 0 4 7` became a 9-gon), believes the header's counts (dropping or
// inventing faces, or allocating for 10^12 of them), and names no line. Here every element is one
// line, counted against the header, and every message names its line.
#include <cmath>

#include "harness/core/errors.h"
#include "harness/mesh/mesh_io.h"
#include "harness/mesh/text_lines.h"

namespace sdb {
namespace {

using text::Line;
using text::LineParser;

// Data lines: the file without comments and blank lines.
std::vector<Line> data_lines(std::string_view text) {
  std::vector<Line> out;
  for (Line l : text::split_lines(text, text::after_bom(text))) {
    if (auto h = l.text.find('#'); h != std::string_view::npos) l.text = text::trim(l.text.substr(0, h));
    if (!l.text.empty()) out.push_back(l);
  }
  return out;
}

struct OffHeader {
  long nv = 0, nf = 0;
  size_t first_element = 0;  // index into the data lines
};

OffHeader read_header(const std::vector<Line>& lines, const std::string& path) {
  if (lines.empty()) throw InputError(path, "empty file");
  const auto head = text::tokens(lines[0].text);
  const std::string_view magic = head[0];
  if (magic.size() < 3 || magic.substr(magic.size() - 3) != "OFF")
    throw InputError(at_line(path, lines[0].number), "missing OFF header (found " + text::quoted(magic) + ")");
  if (magic.find('4') != std::string_view::npos || magic.find('n') != std::string_view::npos)
    throw InputError(at_line(path, lines[0].number), "only 3-D OFF is read, not " + text::quoted(magic));
  OffHeader h;
  std::vector<std::string_view> counts(head.begin() + 1, head.end());
  size_t counts_line = 0;
  if (counts.empty()) {
    if (lines.size() < 2) throw InputError(path, "missing vertex and face counts");
    counts = text::tokens(lines[1].text);
    counts_line = 1;
  }
  const LineParser p(path, lines[counts_line].number);
  if (counts.size() < 2) p.fail("expected vertex and face counts");
  long n[2];
  for (int k = 0; k < 2; ++k) {
    std::string_view t = counts[k];
    auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), n[k]);
    if (ec != std::errc() || end != t.data() + t.size() || n[k] < 0) p.fail("malformed count " + text::quoted(t));
  }
  h.nv = n[0], h.nf = n[1], h.first_element = counts_line + 1;
  const long have = static_cast<long>(lines.size() - h.first_element);
  // Each count held to the lines alone first, so that their sum cannot overflow (tests/fuzz).
  const bool more_announced = h.nv > have || h.nf > have || h.nv + h.nf > have;
  if (more_announced || h.nv + h.nf != have)
    throw InputError(path, "header announces " + std::to_string(h.nv) + " vertices and " + std::to_string(h.nf) +
                               " faces, file has " + std::to_string(have) + " data lines" +
                               (more_announced ? "" : " (more than announced)"));
  return h;
}

void read_face(const LineParser& p, std::string_view line, long nv, ControlMesh& m) {
  const auto tok = text::tokens(line);
  const long n = p.integer(tok[0]);
  if (n < 0) p.fail("negative face size " + text::quoted(tok[0]));
  if (n < 3) p.fail("face has " + std::to_string(n) + " vertices; at least 3 needed");
  // Values after the indices are a colour (OFF allows it); fewer than announced is an error.
  if (static_cast<long>(tok.size()) - 1 < n)
    p.fail("face announces " + std::to_string(n) + " vertices, line has " + std::to_string(tok.size() - 1));
  for (long k = 1; k <= n; ++k) m.face_vertices.push_back(p.index(tok[k], nv, "vertex"));
  m.face_sizes.push_back(static_cast<int>(n));
}

}  // namespace

ControlMesh parse_off(std::string_view text, const std::string& path) {
  const auto lines = data_lines(text);
  const OffHeader h = read_header(lines, path);
  ControlMesh m;
  m.source = path;
  m.positions.reserve(h.nv);
  for (long v = 0; v < h.nv; ++v) {
    const Line& l = lines[h.first_element + v];
    const LineParser p(path, l.number);
    const auto tok = text::tokens(l.text);
    if (tok.size() < 3) p.fail("vertex needs 3 coordinates, found " + std::to_string(tok.size()));
    Point3 pt{};
    for (size_t k = 0; k < tok.size(); ++k) {
      const float c = p.number(tok[k]);  // normals, colours, texture coordinates: checked, not kept
      if (!std::isfinite(c)) p.fail("NaN or Inf coordinate in vertex " + std::to_string(v));
      if (k < 3) pt[k] = c;
    }
    m.positions.push_back(pt);
  }
  for (long f = 0; f < h.nf; ++f) {
    const Line& l = lines[h.first_element + h.nv + f];
    read_face(LineParser(path, l.number), l.text, h.nv, m);
    m.face_lines.push_back(l.number);
  }
  check_mesh_data(m);
  return m;
}

}  // namespace sdb
