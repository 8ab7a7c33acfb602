#include "schemes/geometry-image/creation/cache.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "harness/images/image_io.h"

namespace fs = std::filesystem;

namespace sdb::gim {

namespace {

constexpr const char* kKeyAttribute = "subdivbench_gim_key";
constexpr const char* kFigurePrefix = "subdivbench_gim_";

std::string hex(uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
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

std::optional<CachedImage> ImageCache::load(uint64_t key, int n) const {
  const std::string file = path(key, n);
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return std::nullopt;
  std::optional<images::FloatImage> read = images::image_codec().read_float(file, n, n, 3);
  if (!read || read->strings[kKeyAttribute] != hex(key)) return std::nullopt;
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
