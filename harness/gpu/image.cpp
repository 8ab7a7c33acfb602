#include "harness/gpu/image.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <stdexcept>

namespace sdb::gpu {

void write_png(const Image& image, const std::string& path) {
  if (image.rgba.size() != size_t(image.width) * image.height * 4)
    throw std::invalid_argument("write_png " + path + ": pixel data does not match the image size");
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw std::runtime_error(path + ": cannot write an image here (" + OIIO::geterror() + ")");
  const OIIO::ImageSpec spec(static_cast<int>(image.width), static_cast<int>(image.height), 4, OIIO::TypeDesc::UINT8);
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, image.rgba.data()) || !out->close())
    throw std::runtime_error(path + ": " + out->geterror());
}

Image read_image(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw std::runtime_error(path + ": cannot read (" + OIIO::geterror() + ")");
  const OIIO::ImageSpec& spec = in->spec();
  // A header's size is checked before anything is allocated (a file can announce any size)
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 ||
      double(spec.width) * spec.height * spec.nchannels > double(1 << 30))
    throw std::runtime_error(path + ": announces " + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                             " pixels of " + std::to_string(spec.nchannels) + " channels, past 2^30 values");
  Image image;
  image.width = static_cast<uint32_t>(spec.width);
  image.height = static_cast<uint32_t>(spec.height);
  std::vector<uint8_t> pixels(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, pixels.data()))
    throw std::runtime_error(path + ": " + in->geterror());
  image.rgba.assign(size_t(image.width) * image.height * 4, 255);
  const int channels = std::min(spec.nchannels, 4);
  for (size_t p = 0; p < size_t(image.width) * image.height; ++p)
    for (int c = 0; c < channels; ++c) image.rgba[p * 4 + c] = pixels[p * spec.nchannels + c];
  return image;
}

}  // namespace sdb::gpu
