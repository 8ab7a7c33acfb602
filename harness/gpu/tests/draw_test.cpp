// The graphics path: indexed, instanced triangles into the offscreen target; the same with a
// geometry shader and with tessellation shaders, each changing the colour to show it ran.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "gpu_test_shaders.h"
#include "harness/gpu/gpu.h"
#include "harness/gpu/testing.h"

namespace sdb::gpu {
namespace {

constexpr uint32_t k_width = 64, k_height = 48;
constexpr ClearColour k_black{0.0f, 0.0f, 0.0f, 1.0f};
constexpr std::array<uint8_t, 4> k_clear_pixel{0, 0, 0, 255};
constexpr std::array<uint8_t, 4> k_red{255, 0, 0, 255}, k_green{0, 255, 0, 255}, k_blue{0, 0, 255, 255};
// The triangle sits in the left half; the second instance (or the geometry shader's copy) is
// shifted right by 1 in clip space, i.e. half the target. Pixels at the triangles' centroids:
constexpr uint32_t k_left_x = 16, k_right_x = 48, k_centroid_y = 30;

class DrawTest : public testing::VulkanTest {
 protected:
  GraphicsPipelineDesc triangle_desc() const {
    GraphicsPipelineDesc d;
    d.vertex = gpu_test_shaders::get("triangle.vert");
    d.fragment = gpu_test_shaders::get("colour.frag");
    d.vertex_bindings = {{2 * sizeof(float), false}};
    d.vertex_attributes = {{0, 0, VK_FORMAT_R32G32_SFLOAT, 0}};
    d.push_constant_bytes = 2 * sizeof(float);
    return d;
  }

  // Draws `instances` instances of the triangle (indexed) and reads the target back.
  Image draw(const GraphicsPipelineDesc& desc, uint32_t instances) {
    const std::vector<float> corners{-0.9f, 0.8f, -0.1f, 0.8f, -0.5f, -0.8f};
    const std::vector<uint32_t> indices{0, 1, 2};
    GraphicsPipeline pipeline(ctx(), desc);
    Buffer vertices = device_buffer_with(ctx(), corners, BufferUsage::Vertex, "corners");
    Buffer index_buffer = device_buffer_with(ctx(), indices, BufferUsage::Index, "indices");
    RenderTarget target(ctx(), k_width, k_height);
    const std::array<float, 2> offset{1.0f, 0.0f};
    ctx().run([&](Commands& cmd) {
      target.render(
          cmd,
          [&](Commands& c) {
            c.bind(pipeline);
            c.push(offset);
            c.bind_vertex_buffer(0, vertices);
            c.bind_index_buffer(index_buffer);
            c.draw_indexed(3, instances);
          },
          k_black);
    });
    return target.read(ctx());
  }

  static void expect_clear_outside(const Image& image) {
    EXPECT_EQ(image.pixel(0, 0), k_clear_pixel);
    EXPECT_EQ(image.pixel(k_width - 1, k_height - 1), k_clear_pixel);
    EXPECT_EQ(image.pixel(k_width / 2, 2), k_clear_pixel);  // between the triangles' tops
  }
};

TEST_F(DrawTest, IndexedInstancedTriangles) {
  const Image image = draw(triangle_desc(), 2);
  ASSERT_EQ(image.width, k_width);
  ASSERT_EQ(image.height, k_height);
  EXPECT_EQ(image.pixel(k_left_x, k_centroid_y), k_red);
  EXPECT_EQ(image.pixel(k_right_x, k_centroid_y), k_red);
  expect_clear_outside(image);
}

TEST_F(DrawTest, GeometryShaderEmitsAShiftedCopy) {
  GraphicsPipelineDesc desc = triangle_desc();
  desc.geometry = gpu_test_shaders::get("offset.geom");
  if (auto why = unsupported(ctx(), desc)) GTEST_SKIP() << *why;
  const Image image = draw(desc, 1);
  EXPECT_EQ(image.pixel(k_left_x, k_centroid_y), k_green);
  EXPECT_EQ(image.pixel(k_right_x, k_centroid_y), k_green);
  expect_clear_outside(image);
}

TEST_F(DrawTest, TessellationShadersRun) {
  GraphicsPipelineDesc desc = triangle_desc();
  desc.tess_control = gpu_test_shaders::get("triangle.tesc");
  desc.tess_evaluation = gpu_test_shaders::get("triangle.tese");
  desc.topology = Topology::PatchList;
  desc.patch_control_points = 3;
  if (auto why = unsupported(ctx(), desc)) GTEST_SKIP() << *why;
  const Image image = draw(desc, 1);
  EXPECT_EQ(image.pixel(k_left_x, k_centroid_y), k_blue);
  EXPECT_EQ(image.pixel(k_right_x, k_centroid_y), k_clear_pixel);
  expect_clear_outside(image);
}

TEST_F(DrawTest, InconsistentDescriptionsAreRefused) {
  GraphicsPipelineDesc desc = triangle_desc();
  desc.tess_control = gpu_test_shaders::get("triangle.tesc");  // without an evaluation stage
  EXPECT_THROW(GraphicsPipeline(ctx(), desc), std::invalid_argument);
  desc = triangle_desc();
  desc.vertex_attributes[0].binding = 3;
  EXPECT_THROW(GraphicsPipeline(ctx(), desc), std::invalid_argument);
}

}  // namespace
}  // namespace sdb::gpu
