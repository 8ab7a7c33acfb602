// Image: RGBA8 pixels on the host, and image files through the codec module opened at run time
// (image_io.h). The pixel type lives here, below harness/gpu, which renders into it: the image
// module and the Vulkan module included each other before (issue 41).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace sdb::images {

struct Image {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<uint8_t> rgba;  // rows top to bottom, 4 bytes a pixel

  std::array<uint8_t, 4> pixel(uint32_t x, uint32_t y) const {
    const size_t i = (size_t(y) * width + x) * 4;
    return {rgba[i], rgba[i + 1], rgba[i + 2], rgba[i + 3]};
  }
};

// Throws std::runtime_error naming the path when OpenImageIO cannot write or read it.
void write_png(const Image& image, const std::string& path);
Image read_image(const std::string& path);  // any format OpenImageIO reads, as RGBA8

}  // namespace sdb::images
