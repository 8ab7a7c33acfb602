// Timestamps around a labelled upload / kernel / readback sequence: non-zero and in order.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <random>
#include <vector>

#include "gpu_test_shaders.h"
#include "harness/gpu/gpu.h"
#include "harness/gpu/testing.h"

namespace sdb::gpu {
namespace {

class TimerTest : public testing::VulkanTest {};

struct MaskPush {
  float weights[9];
  uint32_t width;
  uint32_t height;
};

TEST_F(TimerTest, LabelledPassesAreNonZeroAndOrdered) {
  GpuTimer timer(ctx());
  if (!timer.supported()) GTEST_SKIP() << ctx().info().name << " has no timestamps on its graphics+compute queue";
  // The papers' frame size, as a float image.
  const uint32_t w = 1024, h = 768;
  std::vector<float> image(size_t(w) * h);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> dist(0.0f, 1.0f);
  for (float& x : image) x = dist(rng);
  const uint64_t bytes = image.size() * sizeof(float);
  const MaskPush push{{1 / 16.f, 2 / 16.f, 1 / 16.f, 2 / 16.f, 4 / 16.f, 2 / 16.f, 1 / 16.f, 2 / 16.f, 1 / 16.f}, w, h};

  ComputePipeline pipeline(ctx(), {gpu_test_shaders::get("mask3x3.comp"),
                                   {Binding::StorageBuffer, Binding::StorageBuffer}, sizeof(MaskPush)});
  Buffer staging_in = Buffer::upload(ctx(), bytes);
  Buffer src = Buffer::device(ctx(), bytes, BufferUsage::Storage, "src");
  Buffer dst = Buffer::device(ctx(), bytes, BufferUsage::Storage, "dst");
  Buffer staging_out = Buffer::readback(ctx(), bytes);
  DescriptorSet set(pipeline, {src.range(), dst.range()});
  staging_in.write(image);

  const Recording recording = ctx().record([&](Commands& cmd) {
    timer.reset(cmd);
    timer.begin(cmd, PassKind::Upload, "upload");
    cmd.upload(staging_in, src);
    timer.end(cmd);
    timer.begin(cmd, PassKind::Kernel, "mask3x3");
    cmd.bind(pipeline, set);
    cmd.push(push);
    cmd.dispatch((w + 7) / 8, (h + 7) / 8);
    timer.end(cmd);
    timer.begin(cmd, PassKind::Readback, "readback");
    cmd.download(dst, staging_out);
    timer.end(cmd);
  });

  for (int rep = 0; rep < 3; ++rep) {
    const auto start = std::chrono::steady_clock::now();
    ctx().submit(recording);
    const double wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const auto passes = timer.read_passes();
    ASSERT_TRUE(passes.has_value());
    ASSERT_EQ(passes->size(), 3u);
    for (size_t i = 0; i < passes->size(); ++i) {
      const PassTimestamps& p = (*passes)[i];
      EXPECT_GT(p.end_ticks, p.begin_ticks) << p.label;
      EXPECT_GT(p.ms, 0.0) << p.label;
      if (i > 0) {
        EXPECT_LE((*passes)[i - 1].end_ticks, p.begin_ticks) << p.label;
      }
    }
    const GpuTimes times = *timer.read();
    EXPECT_EQ(times.passes.size(), 3u);
    EXPECT_EQ(times.passes[0].label, "upload");
    EXPECT_EQ(times.passes[1].label, "mask3x3");
    EXPECT_EQ(times.passes[2].label, "readback");
    EXPECT_DOUBLE_EQ(times.upload_ms, times.passes[0].ms);
    EXPECT_DOUBLE_EQ(times.kernel_ms, times.passes[1].ms);
    EXPECT_DOUBLE_EQ(times.readback_ms, times.passes[2].ms);
    std::printf("timestamps on %s, 3x3 mask on %ux%u floats (%.1f MiB), run %d: upload %.3f ms, kernel %.3f ms, "
                "readback %.3f ms (submit to fence on the host: %.3f ms)\n",
                ctx().info().name.c_str(), w, h, double(bytes) / (1 << 20), rep + 1, times.upload_ms, times.kernel_ms,
                times.readback_ms, wall_ms);
  }
  // The readback really carried the result.
  std::vector<float> out(image.size());
  staging_out.read(out.data(), bytes);
  EXPECT_NE(out[size_t(w) * 100 + 100], 0.0f);
}

// A pass begun straight after another ended starts at its end timestamp (one timestamp, not
// two: each costs lavapipe a flush); a pass after untimed work writes its own, so that work
// stays out of both.
TEST_F(TimerTest, ConsecutivePassesShareTheirBoundary) {
  GpuTimer timer(ctx());
  if (!timer.supported()) GTEST_SKIP() << ctx().info().name << " has no timestamps on its graphics+compute queue";
  std::vector<Buffer> buffers;  // one per fill: no write-after-write hazards between them
  for (int i = 0; i < 4; ++i) buffers.push_back(Buffer::device(ctx(), 16 << 20, BufferUsage::Storage, "filled"));
  const Recording recording = ctx().record([&](Commands& cmd) {
    timer.reset(cmd);
    timer.begin(cmd, PassKind::Kernel, "a");
    cmd.fill(buffers[0], 1);
    timer.end(cmd);
    timer.begin(cmd, PassKind::Kernel, "b");
    cmd.fill(buffers[1], 2);
    timer.end(cmd);
    cmd.fill(buffers[2], 3);  // untimed
    timer.begin(cmd, PassKind::Kernel, "c");
    cmd.fill(buffers[3], 4);
    timer.end(cmd);
  });
  ctx().submit(recording);
  const auto passes = timer.read_passes();
  ASSERT_TRUE(passes.has_value());
  ASSERT_EQ(passes->size(), 3u);
  EXPECT_EQ((*passes)[1].begin_ticks, (*passes)[0].end_ticks);
  EXPECT_GT((*passes)[2].begin_ticks, (*passes)[1].end_ticks);
  for (const PassTimestamps& p : *passes) EXPECT_GT(p.end_ticks, p.begin_ticks) << p.label;
}

TEST_F(TimerTest, MisuseIsReported) {
  GpuTimer timer(ctx(), 1);
  ctx().run([&](Commands& cmd) {
    timer.reset(cmd);
    EXPECT_THROW(timer.end(cmd), std::logic_error);
    timer.begin(cmd, PassKind::Kernel, "one");
    EXPECT_THROW(timer.begin(cmd, PassKind::Kernel, "nested"), std::logic_error);
    timer.end(cmd);
    EXPECT_THROW(timer.begin(cmd, PassKind::Kernel, "two"), std::logic_error);  // max_passes 1
  });
}

TEST(GpuTimes, SumsByKind) {
  const std::vector<PassTimestamps> passes{{"upload a", PassKind::Upload, 0, 0, 1.0},
                                           {"upload b", PassKind::Upload, 0, 0, 2.0},
                                           {"kernel", PassKind::Kernel, 0, 0, 3.0},
                                           {"draw", PassKind::Draw, 0, 0, 4.0},
                                           {"readback", PassKind::Readback, 0, 0, 5.0}};
  const GpuTimes t = to_gpu_times(passes);
  EXPECT_DOUBLE_EQ(t.upload_ms, 3.0);
  EXPECT_DOUBLE_EQ(t.kernel_ms, 7.0);
  EXPECT_DOUBLE_EQ(t.readback_ms, 5.0);
  ASSERT_EQ(t.passes.size(), 5u);
  EXPECT_EQ(t.passes[3].label, "draw");
}

}  // namespace
}  // namespace sdb::gpu
