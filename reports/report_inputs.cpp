#include "reports/report_inputs.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/core/errors.h"

namespace fs = std::filesystem;

namespace sdb {
namespace {

constexpr int kPicturesSchema = 1;

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

// The eight bytes every PNG file starts with.
bool starts_as_png(const fs::path& p) {
  static constexpr char kSignature[8] = {'\x89', 'P', 'N', 'G', '\r', '\n', '\x1a', '\n'};
  std::ifstream in(p, std::ios::binary);
  char head[8] = {};
  return in.read(head, sizeof head) && std::equal(head, head + 8, kSignature);
}

// A picture's file name, relative to the manifest's folder: a plain name inside it (the manifest
// is data; it must not point the report at files elsewhere), naming a regular file there, not a
// link (report.html inlines it: a link to /etc/passwd would be published as a "PNG"), that is a PNG.
void check_picture_file(const nlohmann::json& name, const fs::path& folder, const std::string& manifest) {
  if (!name.is_string()) throw InputError(manifest, "a picture's file is not a string: " + name.dump());
  const fs::path rel(name.get<std::string>());
  if (rel.empty() || rel.is_absolute() || rel.filename() != rel || rel == "." || rel == "..")
    throw InputError(manifest, "picture file '" + rel.string() + "' is not a file name inside " + folder.string());
  const fs::path file = folder / rel;
  std::error_code ec;
  const fs::file_status link = fs::symlink_status(file, ec);
  if (!fs::exists(link)) throw InputError(file.string(), "picture named in " + manifest + " is missing");
  if (fs::is_symlink(link)) throw InputError(file.string(), "picture named in " + manifest + " is a symbolic link, not a file of its own");
  if (!fs::is_regular_file(link)) throw InputError(file.string(), "picture named in " + manifest + " is not a regular file");
  if (!starts_as_png(file)) throw InputError(file.string(), "picture named in " + manifest + " is not a PNG file");
}

void check_picture(const nlohmann::json& p, const fs::path& folder, const std::string& manifest) {
  for (const char* key : {"scheme", "mesh", "backend", "kind"})
    if (!p.contains(key) || !p[key].is_string()) throw InputError(manifest, std::string("a picture lacks '") + key + "': " + p.dump());
  for (const char* key : {"level", "triangles"})
    if (!p.contains(key) || !p[key].is_number()) throw InputError(manifest, std::string("a picture lacks '") + key + "': " + p.dump());
  const std::string kind = p["kind"];
  if (kind != "shaded" && kind != "deviation") throw InputError(manifest, "picture kind '" + kind + "' is neither shaded nor deviation");
  if (p.contains("deviation_range")) {
    const auto& r = p["deviation_range"];
    if (!r.is_array() || r.size() != 2 || !r[0].is_number() || !r[1].is_number())
      throw InputError(manifest, "deviation_range is not two numbers: " + r.dump());
  }
  // A picture that could not be made has its error instead of a file; the report shows the error.
  if (!p.contains("file") && p.contains("error") && p["error"].is_string()) return;
  check_picture_file(p.value("file", nlohmann::json()), folder, manifest);
}

}  // namespace

std::optional<std::string> find_pictures_manifest(const std::string& out_dir, const std::string& first_input) {
  for (const fs::path& dir : {fs::path(out_dir), fs::path(first_input).parent_path()}) {
    const fs::path p = (dir.empty() ? fs::path(".") : dir) / "pictures" / "pictures.json";
    if (is_file(p)) return p.string();
  }
  return std::nullopt;
}

void check_pictures_manifest(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot read the pictures manifest");
  nlohmann::json j;
  try {
    in >> j;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, std::string("malformed pictures manifest: ") + e.what());
  }
  if (!j.is_object() || j.value("schema", nlohmann::json()) != kPicturesSchema)
    throw InputError(path, "not a pictures manifest of schema " + std::to_string(kPicturesSchema));
  if (!j.contains("available") || !j["available"].is_boolean()) throw InputError(path, "'available' must be true or false");
  if (!j["available"].get<bool>()) {
    if (!j.contains("reason") || !j["reason"].is_string() || j["reason"].get<std::string>().empty())
      throw InputError(path, "pictures unavailable without a reason");
    return;
  }
  const fs::path folder = fs::path(path).parent_path();
  if (j.contains("colour_bar") && !j["colour_bar"].is_null()) check_picture_file(j["colour_bar"], folder, path);
  if (!j.contains("pictures") || !j["pictures"].is_array()) throw InputError(path, "'pictures' must be a list");
  for (const auto& p : j["pictures"]) {
    if (!p.is_object()) throw InputError(path, "a picture is not an object: " + p.dump());
    check_picture(p, folder, path);
  }
}

namespace {

// The length of the UTF-8 sequence starting at text[i], or 0 where none starts there (a stray
// continuation byte, an overlong or surrogate form, a truncated sequence, a byte past U+10FFFF).
size_t utf8_sequence(const std::string& text, size_t i) {
  const auto byte = [&](size_t k) { return k < text.size() ? static_cast<unsigned char>(text[k]) : 0u; };
  const unsigned c = byte(i);
  if (c < 0x80) return 1;
  const size_t n = c >= 0xf0 ? 4 : c >= 0xe0 ? 3 : c >= 0xc2 ? 2 : 0;
  if (n == 0 || c > 0xf4) return 0;
  for (size_t k = 1; k < n; ++k)
    if ((byte(i + k) & 0xc0) != 0x80) return 0;
  const unsigned second = byte(i + 1);
  if ((c == 0xe0 && second < 0xa0) || (c == 0xed && second > 0x9f) || (c == 0xf0 && second < 0x90) || (c == 0xf4 && second > 0x8f))
    return 0;
  return n;
}

// A paper table is Markdown: UTF-8 text without NUL bytes. The line and what is wrong, or "".
std::string not_text(const std::string& text, int& line) {
  line = 1;
  if (const size_t nul = text.find('\0'); nul != std::string::npos) {
    line += static_cast<int>(std::count(text.begin(), text.begin() + long(nul), '\n'));
    return "binary data (a NUL byte), not a Markdown table";
  }
  for (size_t i = 0; i < text.size();) {
    const size_t n = utf8_sequence(text, i);
    if (n == 0) return "not UTF-8 text (byte " + std::to_string(static_cast<unsigned char>(text[i])) + ")";
    if (text[i] == '\n') ++line;
    i += n;
  }
  return "";
}

}  // namespace

void check_paper_tables(const std::vector<std::string>& paths) {
  for (const auto& path : paths) {
    if (!is_file(path)) throw InputError(path, "no such paper table (the Markdown `subdivbench paper ID` writes)");
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    if (!in || text.str().empty()) throw InputError(path, "cannot read the paper table, or it is empty");
    int line = 0;
    if (const std::string why = not_text(text.str(), line); !why.empty()) throw InputError(at_line(path, line), why);
  }
}

}  // namespace sdb
