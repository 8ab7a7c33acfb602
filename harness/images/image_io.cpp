#include "harness/images/image_io.h"

#include <dlfcn.h>

#include <stdexcept>

namespace sdb::images {
namespace {

const ImageCodec* open_codec(std::string& failure) {
  // RTLD_LOCAL: OpenImageIO's symbols stay inside the module.
  void* handle = dlopen(SDB_IMAGE_IO_MODULE, RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    failure = std::string("cannot open the image module ") + SDB_IMAGE_IO_MODULE + " (" + (why ? why : "?") + ")";
    return nullptr;
  }
  using Entry = const ImageCodec* (*)();
  const auto entry = reinterpret_cast<Entry>(dlsym(handle, "sdb_image_codec"));
  if (!entry) {
    failure = std::string("the image module ") + SDB_IMAGE_IO_MODULE + " lacks sdb_image_codec";
    return nullptr;
  }
  return entry();  // the handle stays open for the process's life: the table points into it
}

}  // namespace

const ImageCodec& image_codec() {
  static std::string failure;
  static const ImageCodec* codec = open_codec(failure);
  if (!codec) throw std::runtime_error(failure);
  return *codec;
}

void write_png(const Image& image, const std::string& path) { image_codec().write_rgba8(image, path); }

Image read_image(const std::string& path) { return image_codec().read_rgba8(path); }

}  // namespace sdb::images
