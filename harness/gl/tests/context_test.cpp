// The OpenGL backend's context, where one can be made (Mesa's llvmpipe here and in CI); the
// test says why it skips elsewhere.
#include <gtest/gtest.h>

#include "harness/gl/context.h"
#include "harness/gl/timer.h"

using namespace sdb;

TEST(GlContext, IsAnOpenGL43CoreContextOrSaysWhyNot) {
  const gl::DeviceInfo info = gl::probe();
  if (!info.available) {
    EXPECT_FALSE(info.reason.empty());
    GTEST_SKIP() << "no OpenGL context: " << info.reason;
  }
  EXPECT_FALSE(info.renderer.empty());
  int major = 0, minor = 0;
  ASSERT_EQ(std::sscanf(info.version.c_str(), "%d.%d", &major, &minor), 2) << info.version;
  EXPECT_TRUE(major > 4 || (major == 4 && minor >= 3)) << info.version;
  std::printf("opengl tests run on %s\n", gl::summary(info).c_str());
}

TEST(GlContext, TimestampsTimeLabelledPasses) {
  std::shared_ptr<gl::Context> ctx;
  try {
    ctx = gl::shared_context();
  } catch (const gl::Unavailable& e) {
    GTEST_SKIP() << e.what();
  }
  gl::PassTimer timer(*ctx);
  timer.begin(gl::PassKind::Upload, "up");
  timer.end();
  timer.begin(gl::PassKind::Kernel, "work");
  ctx->functions().Finish();
  timer.end();
  const GpuTimes t = timer.read();
  ASSERT_EQ(t.passes.size(), 2u);
  EXPECT_EQ(t.passes[0].label, "up");
  EXPECT_GE(t.kernel_ms, 0.0);
  EXPECT_EQ(t.readback_ms, 0.0);
  ctx->check("timing two passes");
  timer.clear();
  EXPECT_TRUE(timer.read().passes.empty());
}
