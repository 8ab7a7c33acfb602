#include "harness/images/image_io.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace sdb::images {
namespace {

namespace fs = std::filesystem;

bool openimageio_loaded() {
  std::ifstream maps("/proc/self/maps");
  std::stringstream all;
  all << maps.rdbuf();
  return all.str().find("libOpenImageIO") != std::string::npos;
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("sdb-images-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

// ctest runs each test in a process of its own; run together, this one comes first.
TEST(ImageIo, OpenImageIoIsLoadedOnlyWhenAnImageIsFirstReadOrWritten) {
  EXPECT_FALSE(openimageio_loaded());
  Image image{3, 2, std::vector<uint8_t>(3 * 2 * 4, 7)};
  image_codec().write_rgba8(image, scratch("first.png").string());
  EXPECT_TRUE(openimageio_loaded());
}

TEST(ImageIo, PngRoundTripsPixelForPixel) {
  Image image{5, 3, {}};
  // Opaque: OpenImageIO premultiplies colour by a PNG's alpha, which rounds translucent pixels.
  for (uint32_t i = 0; i < 5 * 3 * 4; ++i) image.rgba.push_back(i % 4 == 3 ? 255 : uint8_t(i * 37 % 256));
  const std::string path = scratch("round.png").string();
  image_codec().write_rgba8(image, path);
  const Image back = image_codec().read_rgba8(path);
  EXPECT_EQ(back.width, 5u);
  EXPECT_EQ(back.height, 3u);
  EXPECT_EQ(back.rgba, image.rgba);
}

TEST(ImageIo, FloatImageRoundTripsWithItsMetadataAndRefusesAnotherSize) {
  FloatImage image;
  image.width = 4, image.height = 2, image.channels = 3;
  for (int i = 0; i < 4 * 2 * 3; ++i) image.samples.push_back(0.1f * float(i) - 1.0f);
  image.strings["sdb_key"] = "00ff";
  image.floats["sdb_figure"] = 2.5f;
  const std::string path = scratch("round.exr").string();
  ASSERT_TRUE(image_codec().write_float(image, path, "zip"));
  const std::optional<FloatImage> back = image_codec().read_float(path, 4, 2, 3);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->samples, image.samples);
  EXPECT_EQ(back->strings.at("sdb_key"), "00ff");
  EXPECT_EQ(back->floats.at("sdb_figure"), 2.5f);
  EXPECT_FALSE(image_codec().read_float(path, 4, 4, 3));
  EXPECT_FALSE(image_codec().read_float(scratch("missing.exr").string(), 4, 2, 3));
}

TEST(ImageIo, AMissingImageIsAnErrorNamingIt) {
  const std::string path = scratch("missing.png").string();
  try {
    image_codec().read_rgba8(path);
    FAIL() << "read a missing file";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sdb::images
