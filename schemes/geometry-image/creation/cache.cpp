#include "schemes/geometry-image/creation/cache.h"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <system_error>

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
  auto in = OIIO::ImageInput::open(file);
  if (!in) return std::nullopt;
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width != n || spec.height != n || spec.nchannels != 3 ||
      spec.get_string_attribute(kKeyAttribute) != hex(key))
    return std::nullopt;
  CachedImage out{GeometryImage(n), {}, file};
  if (!in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, out.image.samples.data())) return std::nullopt;
  for (const OIIO::ParamValue& p : spec.extra_attribs) {
    const std::string name = p.name().string();
    if (name.rfind(kFigurePrefix, 0) == 0 && p.type() == OIIO::TypeDesc::FLOAT)
      out.figures[name.substr(std::string(kFigurePrefix).size())] = p.get_float();
  }
  return out;
}

std::string ImageCache::store(uint64_t key, const GeometryImage& image, const std::map<std::string, double>& figures) const {
  std::error_code ec;
  fs::create_directories(directory_, ec);
  const std::string file = path(key, image.size);
  const std::string temporary = file.substr(0, file.size() - 4) + ".tmp" + std::to_string(::getpid()) + ".exr";
  OIIO::ImageSpec spec(image.size, image.size, 3, OIIO::TypeDesc::FLOAT);
  spec.attribute("compression", "zip");
  spec.attribute(kKeyAttribute, hex(key));
  for (const auto& [name, value] : figures) spec.attribute(kFigurePrefix + name, static_cast<float>(value));
  auto out = OIIO::ImageOutput::create(temporary);
  if (!out || !out->open(temporary, spec)) return {};
  const bool written = out->write_image(OIIO::TypeDesc::FLOAT, image.samples.data());
  out->close();
  if (!written) {
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
