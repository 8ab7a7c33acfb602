#include "schemes/geometry-image/creation/cache.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "harness/core/content_hash.h"
#include "harness/images/image_io.h"

namespace fs = std::filesystem;

namespace sdb::gim {

namespace {

constexpr const char* kKeyAttribute = "subdivbench_gim_key";
constexpr const char* kSizeAttribute = "subdivbench_gim_size";
constexpr const char* kChecksumAttribute = "subdivbench_gim_checksum";
constexpr const char* kFigurePrefix = "subdivbench_gim_";

std::string hex(uint64_t v) { return hex64(v); }

// Over the samples exactly as stored (float32, interleaved, rows top to bottom).
std::string checksum(const std::vector<float>& samples) {
  return hex(fnv1a_64({reinterpret_cast<const char*>(samples.data()), samples.size() * sizeof(float)}));
}

// Why a file read as an image of (key, n) cannot be that image, or "".
std::string mismatch(images::FloatImage& read, uint64_t key, int n) {
  if (read.strings[kKeyAttribute] != hex(key))
    return "written for another key (" + (read.strings[kKeyAttribute].empty() ? "none" : read.strings[kKeyAttribute]) + ")";
  if (read.strings[kSizeAttribute] != std::to_string(n))
    return "its header gives size '" + read.strings[kSizeAttribute] + "', not " + std::to_string(n);
  for (size_t i = 0; i < read.samples.size(); ++i)
    if (!std::isfinite(read.samples[i])) return "sample " + std::to_string(i / 3) + " is not a finite number";
  if (read.strings[kChecksumAttribute] != checksum(read.samples))
    return "checksum mismatch (the samples are not those written with it)";
  return "";
}

}  // namespace

ImageCache::ImageCache(std::string directory) : directory_(std::move(directory)) {}

std::string ImageCache::default_directory() {
  if (const char* env = std::getenv("SUBDIVBENCH_CACHE"); env && *env) return env;
  if (const char* home = std::getenv("HOME"); home && *home) return (fs::path(home) / ".cache" / "subdivbench").string();
  return (fs::temp_directory_path() / "subdivbench-cache").string();
}

std::string ImageCache::path(uint64_t key, int n) const {
  return (fs::path(directory_) / ("gim-" + hex(key) + "-" + std::to_string(n) + ".exr")).string();
}

std::optional<CachedImage> ImageCache::load(uint64_t key, int n, std::string* refused) const {
  const std::string file = path(key, n);
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(file, ec))) return std::nullopt;
  const auto refuse = [&](const std::string& why) -> std::optional<CachedImage> {
    if (refused) *refused = file + ": " + why;
    return std::nullopt;
  };
  if (!fs::is_regular_file(fs::symlink_status(file, ec))) return refuse("not a regular file");
  std::optional<images::FloatImage> read = images::image_codec().read_float(file, n, n, 3);
  if (!read) return refuse("unreadable, or not a " + std::to_string(n) + " x " + std::to_string(n) + " image of three channels");
  if (const std::string why = mismatch(*read, key, n); !why.empty()) return refuse(why);
  CachedImage out{GeometryImage(n), {}, file};
  for (size_t i = 0; i < out.image.samples.size(); ++i)
    for (int c = 0; c < 3; ++c) out.image.samples[i][c] = read->samples[3 * i + c];
  for (const auto& [name, value] : read->floats)
    if (name.rfind(kFigurePrefix, 0) == 0) out.figures[name.substr(std::string(kFigurePrefix).size())] = value;
  return out;
}

std::string ImageCache::store(uint64_t key, const GeometryImage& image, const std::map<std::string, double>& figures) const {
  std::error_code ec;
  fs::create_directories(directory_, ec);
  const std::string file = path(key, image.size);
  const std::string temporary = file.substr(0, file.size() - 4) + ".tmp" + std::to_string(::getpid()) + ".exr";
  images::FloatImage stored;
  stored.width = stored.height = image.size, stored.channels = 3;
  stored.samples.reserve(image.samples.size() * 3);
  for (const Point3& p : image.samples) stored.samples.insert(stored.samples.end(), p.begin(), p.end());
  stored.strings[kKeyAttribute] = hex(key);
  stored.strings[kSizeAttribute] = std::to_string(image.size);
  stored.strings[kChecksumAttribute] = checksum(stored.samples);
  for (const auto& [name, value] : figures) stored.floats[kFigurePrefix + name] = static_cast<float>(value);
  if (!images::image_codec().write_float(stored, temporary, "zip")) {
    fs::remove(temporary, ec);
    return {};
  }
  fs::rename(temporary, file, ec);
  if (ec) {
    fs::remove(temporary, ec);
    return {};
  }
  return file;
}

}  // namespace sdb::gim
