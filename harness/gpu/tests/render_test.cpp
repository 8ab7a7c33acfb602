// The report/fps path: a Tessellation drawn with headlight shading by a camera that frames it,
// read back, written as PNG and timed as a Draw pass.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "harness/gpu/gpu.h"
#include "harness/gpu/testing.h"

namespace sdb::gpu {
namespace {

using testing::is_white;
using testing::uv_sphere;

class RenderTest : public testing::VulkanTest {};

TEST_F(RenderTest, TessellationIsFramedShadedAndWrittenAsPng) {
  const Tessellation mesh = uv_sphere(32, 64, {1, 2, 3}, 2);
  const Image image = render_image(ctx(), mesh, 320, 240);
  // The centre is the sphere, lit head-on: bright but not the white background.
  const auto centre = image.pixel(160, 120);
  EXPECT_FALSE(is_white(centre));
  EXPECT_GT(centre[0], 150);
  // Near the silhouette the normal turns away from the eye: darker than the centre.
  int dark_row_start = -1;
  for (int x = 0; x < 160; ++x)
    if (!is_white(image.pixel(x, 120))) {
      dark_row_start = x;
      break;
    }
  ASSERT_GE(dark_row_start, 0);
  EXPECT_LT(image.pixel(dark_row_start + 1, 120)[0], centre[0]);
  // Framed: the corners are background, and the sphere is not a speck.
  EXPECT_TRUE(is_white(image.pixel(0, 0)));
  EXPECT_TRUE(is_white(image.pixel(319, 239)));
  EXPECT_LT(dark_row_start, 110);

  const std::string path = std::string(SDB_BINARY_DIR) + "/gpu_test_sphere.png";
  write_png(image, path);
  const Image again = read_image(path);
  EXPECT_EQ(again.width, image.width);
  EXPECT_EQ(again.rgba, image.rgba);
}

TEST_F(RenderTest, DrawIsTimedAtThePapersFrameSize) {
  GpuTimer timer(ctx());
  if (!timer.supported()) GTEST_SKIP() << "no timestamps";
  const Tessellation mesh = uv_sphere(256, 512, {1, 2, 3}, 2);  // 262k triangles
  RenderTarget target(ctx(), 1024, 768);
  const GpuMesh gpu_mesh = upload_mesh(ctx(), mesh);
  const MeshRenderer renderer(ctx());
  const Camera camera = frame_tessellation(mesh, target.aspect());
  const Recording frame = ctx().record([&](Commands& cmd) {
    timer.reset(cmd);
    timer.begin(cmd, PassKind::Draw, "draw");
    target.render(cmd, [&](Commands& c) { renderer.draw(c, gpu_mesh.view(), camera); });
    timer.end(cmd);
  });
  for (int i = 0; i < 3; ++i) {
    ctx().submit(frame);
    const GpuTimes t = *timer.read();
    EXPECT_GT(t.kernel_ms, 0.0);
    std::printf("draw of %zu triangles at 1024x768 on %s: %.3f ms (%.1f fps)\n", mesh.num_triangles(),
                ctx().info().name.c_str(), t.kernel_ms, 1000.0 / t.kernel_ms);
  }
  const Image image = target.read(ctx());
  EXPECT_FALSE(is_white(image.pixel(512, 384)));
}

TEST_F(RenderTest, MeshWithoutNormalsIsRefused) {
  Tessellation mesh = uv_sphere(4, 8, {1, 2, 3}, 2);
  mesh.normals.clear();
  EXPECT_THROW(upload_mesh(ctx(), mesh), std::invalid_argument);
}

}  // namespace
}  // namespace sdb::gpu
