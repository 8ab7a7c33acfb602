// Image files (PNG, EXR, whatever OpenImageIO reads) through a module opened at run time.
//
// OpenImageIO brings libjxl and libhwy, whose load-time code runs rdtscp, which valgrind cannot
// decode on some CPUs (this project's CI machine among them): linked into an executable, it stops
// callgrind before main. Opened only where an image is read or written, it leaves every other
// path countable (the gate's deterministic mode, the MiPGH cost claim). The module is
// oiio_codec.cpp; this is the whole of what the rest of the project sees.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "harness/images/image.h"

namespace sdb::images {

// Float samples, interleaved, rows top to bottom, with the file's scalar metadata.
struct FloatImage {
  int width = 0, height = 0, channels = 0;
  std::vector<float> samples;
  std::map<std::string, std::string> strings;
  std::map<std::string, float> floats;
};

// The module's table of entry points (sdb_image_codec() in the module returns it).
struct ImageCodec {
  // std::runtime_error naming the path when the file cannot be written.
  void (*write_rgba8)(const Image& image, const std::string& path);
  // Any format OpenImageIO reads, as RGBA8; std::runtime_error naming the path when it cannot be
  // read or its header announces more than 2^30 values (checked before anything is allocated).
  Image (*read_rgba8)(const std::string& path);
  // The file's float samples when it holds exactly width x height x channels; nullopt otherwise
  // (missing, unreadable, another size).
  std::optional<FloatImage> (*read_float)(const std::string& path, int width, int height, int channels);
  // Writes `image` with its metadata (and `compression`, an OpenImageIO name, or ""); false when it cannot.
  bool (*write_float)(const FloatImage& image, const std::string& path, const std::string& compression);
};

// The module's codec, opened on first use from where this build put it (SDB_IMAGE_IO_MODULE).
// std::runtime_error naming the module when it cannot be opened.
const ImageCodec& image_codec();

}  // namespace sdb::images

extern "C" const sdb::images::ImageCodec* sdb_image_codec();
