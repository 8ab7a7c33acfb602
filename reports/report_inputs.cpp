#include "reports/report_inputs.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

#include "harness/core/errors.h"

namespace fs = std::filesystem;

namespace sdb {
namespace {

constexpr int kPicturesSchema = 1;

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

// A picture's file name, relative to the manifest's folder: a plain name inside it (the manifest
// is data; it must not point the report at files elsewhere), naming a file that exists.
void check_picture_file(const nlohmann::json& name, const fs::path& folder, const std::string& manifest) {
  if (!name.is_string()) throw InputError(manifest, "a picture's file is not a string: " + name.dump());
  const fs::path rel(name.get<std::string>());
  if (rel.empty() || rel.is_absolute() || rel.filename() != rel || rel == "." || rel == "..")
    throw InputError(manifest, "picture file '" + rel.string() + "' is not a file name inside " + folder.string());
  if (!is_file(folder / rel)) throw InputError((folder / rel).string(), "picture named in " + manifest + " is missing");
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

void check_paper_tables(const std::vector<std::string>& paths) {
  for (const auto& path : paths) {
    if (!is_file(path)) throw InputError(path, "no such paper table (the Markdown `subdivbench paper ID` writes)");
    std::ifstream in(path);
    std::string first;
    if (!in || !std::getline(in, first)) throw InputError(path, "cannot read the paper table, or it is empty");
  }
}

}  // namespace sdb
