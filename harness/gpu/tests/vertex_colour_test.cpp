// Colour per vertex (the report's deviation pictures): each vertex's colour comes out where that
// vertex is drawn, scaled by the same headlight shading as a single-colour picture.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "harness/gpu/gpu.h"
#include "harness/gpu/testing.h"

namespace sdb::gpu {
namespace {

using testing::is_white;
using testing::uv_sphere;

class VertexColourTest : public testing::VulkanTest {};


void expect_near_colour(const std::array<uint8_t, 4>& pixel, const Point3& colour, int tolerance) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(int(pixel[c]), int(std::lround(255 * colour[c])), tolerance) << "channel " << c;
}

TEST_F(VertexColourTest, OneColourComesOutWhereTheSurfaceFacesTheEye) {
  const Tessellation sphere = uv_sphere(48, 96);
  const Point3 colour{0.2f, 0.6f, 0.9f};
  PictureOptions options;
  options.width = 320, options.height = 240;
  const Image image = render_image(ctx(), sphere, std::vector<Point3>(sphere.positions.size(), colour), options);
  ASSERT_EQ(image.width, 320u);
  ASSERT_EQ(image.height, 240u);
  // At the centre the normal points at the eye: the Lambert term is 1, the colour unscaled.
  expect_near_colour(image.pixel(160, 120), colour, 6);
  EXPECT_TRUE(is_white(image.pixel(0, 0)));
  // Towards the silhouette the same colour is darker, by the same factor in every channel.
  int first = -1;
  for (int x = 0; x < 160 && first < 0; ++x)
    if (!is_white(image.pixel(x, 120))) first = x;
  ASSERT_GE(first, 0);
  const auto edge = image.pixel(first + 3, 120);
  EXPECT_LT(edge[2], image.pixel(160, 120)[2]);
  EXPECT_LT(edge[0], edge[1]);
  EXPECT_LT(edge[1], edge[2]);
}

TEST_F(VertexColourTest, EachHalfKeepsItsOwnColour) {
  // Upper half (y > 0) red, lower half green: the camera keeps y up.
  const Tessellation sphere = uv_sphere(48, 96);
  std::vector<Point3> colours;
  for (const Point3& p : sphere.positions) colours.push_back(p[1] > 0 ? Point3{0.9f, 0.1f, 0.1f} : Point3{0.1f, 0.8f, 0.1f});
  PictureOptions options;
  options.width = 320, options.height = 240;
  options.background = {0.0f, 0.0f, 0.0f, 1.0f};
  const Image image = render_image(ctx(), sphere, colours, options);
  const auto top = image.pixel(160, 80), bottom = image.pixel(160, 170), corner = image.pixel(2, 2);
  EXPECT_GT(top[0], 2 * top[1]);
  EXPECT_GT(bottom[1], 2 * bottom[0]);
  EXPECT_EQ(corner[0] + corner[1] + corner[2], 0);  // the background asked for
}

TEST_F(VertexColourTest, SupersamplingKeepsTheSizeAndSmoothsTheSilhouette) {
  const Tessellation sphere = uv_sphere(24, 48);
  const std::vector<Point3> black(sphere.positions.size(), Point3{0, 0, 0});
  PictureOptions options;
  options.width = 160, options.height = 120, options.ambient = 0;
  options.supersample = 1;
  const Image plain = render_image(ctx(), sphere, black, options);
  options.supersample = 3;
  const Image smooth = render_image(ctx(), sphere, black, options);
  ASSERT_EQ(smooth.width, 160u);
  ASSERT_EQ(smooth.height, 120u);
  // A black surface on white: grey pixels are partly covered ones, which only the averaged
  // picture has (beyond a few where the rasterizer's coverage rounds).
  auto grey_pixels = [](const Image& image) {
    int n = 0;
    for (uint32_t y = 0; y < image.height; ++y)
      for (uint32_t x = 0; x < image.width; ++x) {
        const auto p = image.pixel(x, y);
        n += p[0] > 40 && p[0] < 215;
      }
    return n;
  };
  EXPECT_GT(grey_pixels(smooth), grey_pixels(plain) + 50);
}

TEST_F(VertexColourTest, FramePointsFillsThePictureUpToItsMargin) {
  const Tessellation sphere = uv_sphere(48, 96);
  PictureOptions options;
  options.width = 200, options.height = 100, options.supersample = 1;
  options.camera = frame_points(sphere.positions, 2.0f, {0.3f, 0.2f, 1.0f}, 0.05f);
  const Image image = render_image(ctx(), sphere, std::vector<Point3>(sphere.positions.size(), Point3{0, 0, 0}), options);
  uint32_t top = image.height, bottom = 0, left = image.width, right = 0;
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x)
      if (!is_white(image.pixel(x, y))) {
        top = std::min(top, y), bottom = std::max(bottom, y);
        left = std::min(left, x), right = std::max(right, x);
      }
  // The height binds (aspect 2): 5 pixels free above and below, the sphere centred across.
  EXPECT_NEAR(top, 5, 2);
  EXPECT_NEAR(bottom, 94, 2);
  EXPECT_NEAR(int(left) + int(right), 199, 3);
  EXPECT_NEAR(right - left, bottom - top, 3);
}

TEST_F(VertexColourTest, ColourCountMustMatchTheVertices) {
  const Tessellation sphere = uv_sphere(4, 8);
  EXPECT_THROW(render_image(ctx(), sphere, std::vector<Point3>(3), PictureOptions{}), std::invalid_argument);
}

}  // namespace
}  // namespace sdb::gpu
