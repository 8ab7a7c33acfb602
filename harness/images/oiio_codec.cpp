// The image module (image_io.h): OpenImageIO behind a table of plain functions.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <stdexcept>

#include "harness/images/image_io.h"

namespace sdb::images {
namespace {

void write_rgba8(const Image& image, const std::string& path) {
  if (image.rgba.size() != size_t(image.width) * image.height * 4)
    throw std::invalid_argument("write_png " + path + ": pixel data does not match the image size");
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw std::runtime_error(path + ": cannot write an image here (" + OIIO::geterror() + ")");
  const OIIO::ImageSpec spec(static_cast<int>(image.width), static_cast<int>(image.height), 4, OIIO::TypeDesc::UINT8);
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, image.rgba.data()) || !out->close())
    throw std::runtime_error(path + ": " + out->geterror());
}

Image read_rgba8(const std::string& path) {
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

std::optional<FloatImage> read_float(const std::string& path, int width, int height, int channels) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return std::nullopt;
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width != width || spec.height != height || spec.nchannels != channels) return std::nullopt;
  FloatImage out;
  out.width = width, out.height = height, out.channels = channels;
  out.samples.resize(size_t(width) * height * channels);
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, out.samples.data())) return std::nullopt;
  for (const OIIO::ParamValue& p : spec.extra_attribs) {
    if (p.type() == OIIO::TypeDesc::FLOAT) out.floats[p.name().string()] = p.get_float();
    if (p.type() == OIIO::TypeDesc::STRING) out.strings[p.name().string()] = p.get_string();
  }
  return out;
}

bool write_float(const FloatImage& image, const std::string& path, const std::string& compression) {
  if (image.samples.size() != size_t(image.width) * image.height * image.channels) return false;
  OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
  if (!compression.empty()) spec.attribute("compression", compression);
  for (const auto& [name, value] : image.strings) spec.attribute(name, value);
  for (const auto& [name, value] : image.floats) spec.attribute(name, value);
  auto out = OIIO::ImageOutput::create(path);
  if (!out || !out->open(path, spec)) return false;
  const bool written = out->write_image(OIIO::TypeDesc::FLOAT, image.samples.data());
  return out->close() && written;
}

const ImageCodec k_codec{write_rgba8, read_rgba8, read_float, write_float};

}  // namespace
}  // namespace sdb::images

extern "C" const sdb::images::ImageCodec* sdb_image_codec() { return &sdb::images::k_codec; }
