// PLY checked before OpenMesh reads it. OpenMesh believes the header (allocating for announced
// counts, dropping or inventing faces when they lie), loops forever on a file without end_header,
// prints its own noise and names no line. This pass reads the header, walks the body once
// (binary: every element's bytes; ASCII: one line per element, every token), and refuses with the
// line or element; only then does OpenMesh parse a file known to be consistent.
#include "harness/mesh/ply_check.h"

#include <cmath>
#include <cstring>

#include "harness/core/errors.h"
#include "harness/mesh/text_lines.h"

namespace sdb {
namespace {

struct Property {
  std::string name;
  int size = 0, count_size = 0;  // count_size > 0: a list, its count of this many bytes
  bool is_float = false, count_float = false;
  bool is_unsigned = false;  // of the values (a list's items)
};

bool unsigned_type(std::string_view t) { return t.front() == 'u'; }

std::string index_out_of_range(std::string_view index, long vertices) {
  return "vertex index " + std::string(index.substr(0, 40)) + " out of range (mesh has " + std::to_string(vertices) + " vertices)";
}

struct Element {
  std::string name;
  long count = 0;
  std::vector<Property> properties;
  int line = 0;  // of its header line
};

// The face element's list of vertex indices, which OpenMesh reads as int: a uint index past
// INT_MAX (4294967295, say) would reach our checks as -1, so indices are held to the vertex count
// here, quoted as the file writes them.
bool is_vertex_indices(const Element& e, const Property& p) {
  return e.name == "face" && p.count_size && !p.is_float && (p.name == "vertex_indices" || p.name == "vertex_index");
}

enum class Format { Ascii, BinaryLittle, BinaryBig };

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  size_t body = 0;       // byte offset of the body
  int body_line = 0;     // line number of the body's first line
};

// Size in bytes and float-ness of a PLY scalar type; 0 if unknown.
std::pair<int, bool> scalar_type(std::string_view t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return {1, false};
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return {2, false};
  if (t == "int" || t == "uint" || t == "int32" || t == "uint32") return {4, false};
  if (t == "float" || t == "float32") return {4, true};
  if (t == "double" || t == "float64") return {8, true};
  return {0, false};
}

Property parse_property(const text::LineParser& p, const std::vector<std::string_view>& tok) {
  Property prop;
  if (tok.size() == 5 && tok[1] == "list") {
    auto [cs, cf] = scalar_type(tok[2]);
    auto [is, inf] = scalar_type(tok[3]);
    if (!cs || !is) p.fail("unknown list type '" + std::string(tok[2]) + " " + std::string(tok[3]) + "'");
    prop = {std::string(tok[4]), is, cs, inf, cf, unsigned_type(tok[3])};
  } else if (tok.size() == 3) {
    auto [s, f] = scalar_type(tok[1]);
    if (!s) p.fail("unknown property type " + text::quoted(tok[1]));
    prop = {std::string(tok[2]), s, 0, f, false, unsigned_type(tok[1])};
  } else {
    p.fail("malformed property line");
  }
  return prop;
}

// An element without properties takes no bytes, so a binary body cannot bound its count: walking
// (or letting OpenMesh walk) 10^18 empty instances hangs (tests/fuzz/regressions/ply).
void require_properties(const Element& e, const std::string& path) {
  if (e.count > 0 && e.properties.empty())
    text::LineParser(path, e.line).fail("element '" + e.name + "' announces " + std::to_string(e.count) +
                                        " instances but no properties");
}

// OpenMesh splits the header on every isspace byte and reads a NUL as part of a word; ours splits on
// blanks. A form feed, vertical tab or NUL inside a line made the two read different words, and
// OpenMesh looped forever on the count it could not parse (tests/fuzz/regressions/ply). A header is
// ASCII text: control bytes are refused on every line, bytes past ASCII outside comments.
void require_header_text(const text::LineParser& p, std::string_view line, bool comment) {
  for (const char ch : line) {
    const auto c = static_cast<unsigned char>(ch);
    if ((c < 0x20 && c != '\t' && c != '\r') || c == 0x7f || (c >= 0x80 && !comment))
      p.fail("byte " + std::to_string(c) + " in the header (a PLY header is ASCII text)");
  }
}

Header read_header(std::string_view data, const std::string& path) {
  if (data.empty()) throw InputError(path, "empty file");
  Header h;
  size_t pos = 0;
  int no = 0;
  bool have_format = false;
  while (true) {
    if (pos >= data.size()) throw InputError(path, "header has no end_header line");
    const auto [raw, next] = text::next_line(data, pos);
    if (next == data.size() && raw.size() == data.size() - pos) throw InputError(path, "header has no end_header line");
    const std::string_view line = text::trim(raw);
    pos = next;
    const text::LineParser p(path, ++no);
    const auto tok = text::tokens(line);
    if (no == 1) {
      if (line != "ply") p.fail("not a PLY file (first line is not 'ply')");
      continue;
    }
    const bool comment = !tok.empty() && (tok[0] == "comment" || tok[0] == "obj_info");
    require_header_text(p, line, comment);
    if (tok.empty() || comment) continue;
    if (tok[0] == "end_header") break;
    if (tok[0] == "format") {
      if (tok.size() != 3) p.fail("malformed format line");
      if (tok[1] == "ascii") h.format = Format::Ascii;
      else if (tok[1] == "binary_little_endian") h.format = Format::BinaryLittle;
      else if (tok[1] == "binary_big_endian") h.format = Format::BinaryBig;
      else p.fail("unknown PLY format " + text::quoted(tok[1]));
      // OpenMesh reads the version as a number and loops forever on anything else (tests/fuzz).
      if (tok[2] != "1.0") p.fail("unknown PLY version " + text::quoted(tok[2]) + " (1.0 is the only one)");
      have_format = true;
    } else if (tok[0] == "element") {
      if (tok.size() != 3) p.fail("malformed element line");
      const long n = p.integer(tok[2]);
      if (n < 0) p.fail("negative element count " + text::quoted(tok[2]));
      h.elements.push_back({std::string(tok[1]), n, {}, no});
    } else if (tok[0] == "property") {
      if (h.elements.empty()) p.fail("property before any element");
      h.elements.back().properties.push_back(parse_property(p, tok));
    } else {
      p.fail("unknown header line " + text::quoted(line));
    }
  }
  if (!have_format) throw InputError(path, "header has no format line");
  for (const Element& e : h.elements) require_properties(e, path);
  h.body = pos, h.body_line = no + 1;
  return h;
}

// ---- binary: walk every element's bytes

struct ByteReader {
  std::string_view data;
  size_t pos;
  bool big_endian;

  bool skip(size_t n) {
    if (data.size() - pos < n) return false;
    pos += n;
    return true;
  }
  // A list count, as a signed or unsigned integer of `size` bytes (float counts refused by caller).
  bool count(int size, long& out) { return integer(size, false, out); }
  // An integer of `size` bytes (at most 4), signed or not.
  bool integer(int size, bool is_signed, long& out) {
    if (data.size() - pos < size_t(size)) return false;
    unsigned char b[8] = {};
    std::memcpy(b, data.data() + pos, size);
    pos += size;
    uint64_t v = 0;
    for (int k = 0; k < size; ++k) v |= uint64_t(b[big_endian ? size - 1 - k : k]) << (8 * k);
    const bool negative = is_signed && size < 8 && (v >> (8 * size - 1)) & 1;
    out = negative ? static_cast<long>(v) - (long(1) << (8 * size)) : static_cast<long>(v);
    return true;
  }
};

long vertex_count(const Header& h) {
  for (const Element& e : h.elements)
    if (e.name == "vertex") return e.count;
  return 0;
}

void walk_binary(const Header& h, std::string_view data, const std::string& path) {
  ByteReader r{data, h.body, h.format == Format::BinaryBig};
  const long vertices = vertex_count(h);
  for (const Element& e : h.elements)
    for (long i = 0; i < e.count; ++i)
      for (const Property& p : e.properties) {
        const std::string where = e.name + " " + std::to_string(i);
        long n = 1;
        if (p.count_size && (p.count_float || !r.count(p.count_size, n)))
          throw InputError(path, "file ends inside " + where + " of the " + std::to_string(e.count) + " the header announces");
        if (is_vertex_indices(e, p) && p.size <= 4) {
          for (long k = 0; k < n; ++k) {
            long index = 0;
            if (!r.integer(p.size, !p.is_unsigned, index))
              throw InputError(path, "file ends inside " + where + " of the " + std::to_string(e.count) + " the header announces");
            if (index < 0 || index >= vertices) throw InputError(path, where + ": " + index_out_of_range(std::to_string(index), vertices));
          }
        } else if (!r.skip(size_t(n) * p.size)) {
          throw InputError(path, "file ends inside " + where + " of the " + std::to_string(e.count) + " the header announces");
        }
      }
  // A trailing newline or two is a writer's habit; more is data the header does not announce.
  if (data.size() - r.pos > 2)
    throw InputError(path, std::to_string(data.size() - r.pos) + " bytes after the last element the header announces");
}

// ---- ASCII: one line per element

void check_ascii_element(const text::LineParser& p, const Element& e, std::string_view line, long vertices) {
  const auto tok = text::tokens(line);
  size_t t = 0;
  for (const Property& prop : e.properties) {
    long n = 1;
    if (prop.count_size) {
      if (t >= tok.size()) p.fail(e.name + " line ends before its '" + prop.name + "' list");
      n = p.integer(tok[t++]);
      if (n < 0) p.fail("negative list size " + text::quoted(tok[t - 1]));
      if (e.name == "face" && n < 3) p.fail("face has " + std::to_string(n) + " vertices; at least 3 needed");
      if (static_cast<long>(tok.size() - t) < n)
        p.fail(e.name + " announces " + std::to_string(n) + " vertices, line has " + std::to_string(tok.size() - t));
    }
    for (long k = 0; k < n; ++k) {
      if (t >= tok.size()) p.fail(e.name + " line has too few values for its properties");
      if (prop.is_float) {
        const float v = p.number(tok[t]);
        if (!std::isfinite(v)) p.fail("NaN or Inf in " + e.name + " property '" + prop.name + "'");
      } else {
        const long v = p.integer(tok[t]);
        if (is_vertex_indices(e, prop) && (v < 0 || v >= vertices)) p.fail(index_out_of_range(tok[t], vertices));
      }
      ++t;
    }
  }
  if (t != tok.size()) p.fail(e.name + " line has " + std::to_string(tok.size()) + " values, its properties " + std::to_string(t));
}

std::vector<int> check_ascii(const Header& h, std::string_view data, const std::string& path) {
  std::vector<text::Line> lines;
  for (const text::Line& l : text::split_lines(data, h.body, h.body_line))
    if (!l.text.empty()) lines.push_back(l);
  const long have = static_cast<long>(lines.size());
  long announced = 0;
  std::string counts;
  for (const Element& e : h.elements) {
    counts += (counts.empty() ? "" : " and ") + std::to_string(e.count) + " " + e.name;
    announced += std::min(e.count, have + 1);  // each bounded, so the sum cannot overflow
  }
  if (announced != have)
    throw InputError(path, "header announces " + counts + " elements, file has " + std::to_string(have) + " data lines");
  std::vector<int> face_lines;
  size_t next = 0;
  for (const Element& e : h.elements)
    for (long i = 0; i < e.count; ++i, ++next) {
      check_ascii_element(text::LineParser(path, lines[next].number), e, lines[next].text, vertex_count(h));
      if (e.name == "face") face_lines.push_back(lines[next].number);
    }
  return face_lines;
}

}  // namespace

PlyLayout check_ply(std::string_view data, const std::string& path) {
  const Header h = read_header(data, path);
  PlyLayout out;
  bool has_xyz = false, has_indices = false;
  for (const Element& e : h.elements) {
    if (e.name == "vertex") {
      out.vertices = e.count;
      int xyz = 0;
      for (const Property& p : e.properties) xyz += !p.count_size && (p.name == "x" || p.name == "y" || p.name == "z");
      has_xyz = xyz == 3;
    } else if (e.name == "face") {
      out.faces = e.count;
      for (const Property& p : e.properties)
        has_indices |= p.count_size && !p.is_float && (p.name == "vertex_indices" || p.name == "vertex_index");
    }
  }
  if (!has_xyz) throw InputError(path, "no vertex element with x, y and z properties");
  if (!has_indices) throw InputError(path, "no face element with a vertex_indices list");
  if (h.format == Format::Ascii) out.face_lines = check_ascii(h, data, path);
  else walk_binary(h, data, path);
  out.body = h.body;
  out.ascii = h.format == Format::Ascii;
  return out;
}

std::string with_lf_line_ends(std::string_view data, const PlyLayout& layout) {
  const size_t text_end = layout.ascii ? data.size() : layout.body;
  std::string out;
  out.reserve(data.size());
  for (size_t pos = 0; pos < text_end;) {
    const auto [line, next] = text::next_line(data.substr(0, text_end), pos);
    out.append(line);
    if (next > pos + line.size()) out += '\n';
    pos = next;
  }
  out.append(data.substr(text_end));
  return out;
}

}  // namespace sdb
