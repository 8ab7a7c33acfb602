#include "harness/gpu/image.h"

#include "harness/images/image_io.h"

namespace sdb::gpu {

void write_png(const Image& image, const std::string& path) { images::image_codec().write_rgba8(image, path); }

Image read_image(const std::string& path) { return images::image_codec().read_rgba8(path); }

}  // namespace sdb::gpu
