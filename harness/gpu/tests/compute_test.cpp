// A 3x3 mask applied on the device equals the CPU's result bit for bit; a recorded command
// buffer can be submitted again; specialization constants reach the shader.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "gpu_test_shaders.h"
#include "harness/gpu/gpu.h"
#include "harness/gpu/testing.h"

namespace sdb::gpu {
namespace {

class ComputeTest : public testing::VulkanTest {};

struct MaskPush {
  float weights[9];
  uint32_t width;
  uint32_t height;
};

// Same order as mask3x3.comp: rows top to bottom, each left to right, multiply then add, each
// rounded to float (this file is built with -ffp-contract=off, so no FMA here either).
std::vector<float> mask_on_cpu(const std::vector<float>& src, uint32_t w, uint32_t h, const float* weights) {
  std::vector<float> dst(src.size());
  for (int y = 0; y < int(h); ++y)
    for (int x = 0; x < int(w); ++x) {
      float sum = 0.0f;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int sx = std::clamp(x + dx, 0, int(w) - 1);
          const int sy = std::clamp(y + dy, 0, int(h) - 1);
          const float product = weights[(dy + 1) * 3 + (dx + 1)] * src[size_t(sy) * w + sx];
          sum = sum + product;
        }
      dst[size_t(y) * w + x] = sum;
    }
  return dst;
}

// Values in [1e-3, 1): no subnormals, which a GPU may flush to zero.
std::vector<float> random_image(uint32_t w, uint32_t h) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<float> dist(1e-3f, 1.0f);
  std::vector<float> v(size_t(w) * h);
  for (float& x : v) x = dist(rng);
  return v;
}

TEST_F(ComputeTest, Mask3x3MatchesCpuBitForBit) {
  const uint32_t w = 333, h = 217;  // not multiples of the 8x8 work group
  const std::vector<float> image = random_image(w, h);
  const MaskPush push{{0.07f, 0.13f, 0.05f, 0.11f, 0.28f, 0.09f, 0.06f, 0.12f, 0.09f}, w, h};

  ComputePipeline pipeline(ctx(), {gpu_test_shaders::get("mask3x3.comp"),
                                   {Binding::StorageBuffer, Binding::StorageBuffer}, sizeof(MaskPush)});
  Buffer src = device_buffer_with(ctx(), image, BufferUsage::Storage, "src");
  Buffer dst = Buffer::device(ctx(), src.size(), BufferUsage::Storage, "dst");
  DescriptorSet set(pipeline, {src.range(), dst.range()});
  ctx().run([&](Commands& cmd) {
    cmd.bind(pipeline, set);
    cmd.push(push);
    cmd.dispatch((w + 7) / 8, (h + 7) / 8);
  });
  const std::vector<float> gpu = download_as<float>(ctx(), dst, image.size());
  const std::vector<float> cpu = mask_on_cpu(image, w, h, push.weights);

  size_t differing = 0, first = 0;
  for (size_t i = 0; i < cpu.size(); ++i)
    if (std::memcmp(&cpu[i], &gpu[i], sizeof(float)) != 0 && differing++ == 0) first = i;
  EXPECT_EQ(differing, 0u) << "first difference at pixel " << first << ": cpu " << cpu[first] << ", gpu "
                           << gpu[first];
}

// `precise` functions called in an unrolled loop keep NoContraction in every copy: the embedded
// shaders are built so (cmake/Shaders.cmake), and the schemes' bit-identity with the CPU rests on
// it. The multiply-adds' inputs cancel, so a fused multiply-add differs from the rounded multiply
// then add in most of them; the limit masks' inputs are random.
TEST_F(ComputeTest, PreciseFunctionsKeepNoContractionInEveryCopy) {
  constexpr size_t kInputs = 12, kCopies = 4;
  const uint32_t invocations = 4096;
  const size_t results = kCopies * invocations;
  std::mt19937 rng(2026);
  std::uniform_real_distribution<float> dist(0.5f, 2.0f);
  std::vector<float> src(kInputs * results);
  for (size_t j = 0; j < results; ++j) {
    float* in = &src[kInputs * j];
    for (size_t q = 0; q < kInputs; ++q) in[q] = dist(rng);
    in[2] = -in[0] * in[1] * (1.0f + 1e-6f * dist(rng));
  }
  ComputePipeline pipeline(ctx(), {gpu_test_shaders::get("precise_calls.comp"),
                                   {Binding::StorageBuffer, Binding::StorageBuffer}, sizeof(uint32_t)});
  Buffer in = device_buffer_with(ctx(), src, BufferUsage::Storage, "inputs");
  Buffer out = Buffer::device(ctx(), 2 * results * sizeof(float), BufferUsage::Storage, "results");
  DescriptorSet set(pipeline, {in.range(), out.range()});
  ctx().run([&](Commands& cmd) {
    cmd.bind(pipeline, set);
    cmd.push(invocations);
    cmd.dispatch((invocations + 63) / 64);
  });
  const std::vector<float> gpu = download_as<float>(ctx(), out, 2 * results);
  size_t differing[2][kCopies] = {}, fused_differs = 0;
  for (size_t j = 0; j < results; ++j) {
    const float* v = &src[kInputs * j];
    // This file is built with -ffp-contract=off: each operation rounds, as NoContraction asks.
    const float product = v[0] * v[1];
    const float multiply_add = product + v[2];
    fused_differs += std::fma(v[0], v[1], v[2]) != multiply_add;
    const float edges = (v[4] + v[5]) + (v[6] + v[7]), corners = (v[8] + v[9]) + (v[10] + v[11]);
    const float limit = ((16.0f * v[3] + 4.0f * edges) + corners) * (1.0f / 36.0f);
    for (int q = 0; q < 2; ++q) {
      const float cpu = q == 0 ? multiply_add : limit;
      differing[q][j % kCopies] += std::memcmp(&cpu, &gpu[2 * j + q], sizeof(float)) != 0;
    }
  }
  EXPECT_GT(fused_differs, results / 2) << "the inputs do not tell a fused multiply-add apart";
  for (size_t k = 0; k < kCopies; ++k) {
    EXPECT_EQ(differing[0][k], 0u) << "multiply-add, copy " << k;
    EXPECT_EQ(differing[1][k], 0u) << "limit mask, copy " << k;
  }
}

TEST_F(ComputeTest, RecordingSubmitsAgainAndSpecializationConstantsApply) {
  const uint32_t count = 1000;
  std::vector<float> values(count);
  for (uint32_t i = 0; i < count; ++i) values[i] = float(i);
  const float factor = 2.0f;
  uint32_t factor_bits;
  std::memcpy(&factor_bits, &factor, sizeof factor_bits);
  ComputePipeline pipeline(ctx(), {gpu_test_shaders::get("scale.comp"), {Binding::StorageBuffer}, 4, {{0, factor_bits}}});
  Buffer data = device_buffer_with(ctx(), values, BufferUsage::Storage, "data");
  DescriptorSet set(pipeline, {data.range()});
  const Recording recording = ctx().record([&](Commands& cmd) {
    cmd.bind(pipeline, set);
    cmd.push(count);
    cmd.dispatch(groups_for(count, 64, ctx().limits()));
  });
  for (int i = 0; i < 3; ++i) ctx().submit(recording);
  const std::vector<float> out = download_as<float>(ctx(), data, count);
  for (uint32_t i = 0; i < count; ++i) ASSERT_EQ(out[i], 8.0f * float(i)) << "element " << i;
}

// The same description gives the same pipeline (compiled once); another specialization another,
// which computes its own factor.
TEST_F(ComputeTest, SharedPipelinesAreOnePerDescription) {
  auto desc = [](float factor) {
    uint32_t bits;
    std::memcpy(&bits, &factor, sizeof bits);
    return ComputePipelineDesc{gpu_test_shaders::get("scale.comp"), {Binding::StorageBuffer}, 4, {{0, bits}}};
  };
  const auto twice = shared_compute_pipeline(ctx(), desc(2.0f));
  EXPECT_EQ(twice, shared_compute_pipeline(ctx(), desc(2.0f)));
  const auto thrice = shared_compute_pipeline(ctx(), desc(3.0f));
  ASSERT_NE(twice, thrice);
  const std::vector<float> values = {1.0f, 2.0f};
  Buffer data = device_buffer_with(ctx(), values, BufferUsage::Storage, "data");
  DescriptorSet set(*thrice, {data.range()});
  ctx().run([&](Commands& cmd) {
    cmd.bind(*thrice, set);
    cmd.push(uint32_t(2));
    cmd.dispatch(groups_for(2, 64, ctx().limits()));
  });
  EXPECT_EQ(download_as<float>(ctx(), data, 2), (std::vector<float>{3.0f, 6.0f}));
}

TEST_F(ComputeTest, WrongBindingsAreRefusedBeforeVulkanSeesThem) {
  ComputePipeline pipeline(ctx(), {gpu_test_shaders::get("scale.comp"), {Binding::StorageBuffer}, 4});
  Buffer uniform_only = Buffer::device(ctx(), 256, BufferUsage::Uniform, "uniform only");
  Buffer storage = Buffer::device(ctx(), 256, BufferUsage::Storage, "storage");
  EXPECT_THROW(DescriptorSet(pipeline, {uniform_only.range()}), std::invalid_argument);
  EXPECT_THROW(DescriptorSet(pipeline, {storage.range(), storage.range()}), std::invalid_argument);
  EXPECT_THROW(DescriptorSet(pipeline, {storage.range(300)}), std::invalid_argument);
  ctx().run([&](Commands& cmd) {
    cmd.bind(pipeline);
    EXPECT_THROW(cmd.push_constants(&pipeline, 8), std::invalid_argument);  // declared 4 bytes
  });
}

// Texel buffers (the lavapipe fast path for reads and writes, pipeline.h): a vec4 view in, a
// float view out, from an offset into each buffer; the result is the CPU's to the bit.
TEST_F(ComputeTest, TexelBuffersReadAndWriteThroughViews) {
  const uint32_t count = 1000, skip = 16;  // views start `skip` texels in (minTexelBufferOffsetAlignment <= 256 B)
  std::vector<float> values(4 * size_t(count + skip));
  for (size_t k = 0; k < values.size(); ++k) values[k] = 0.25f * float(k % 97) + 1.0f;
  ComputePipeline pipeline(ctx(), {gpu_test_shaders::get("texel_copy.comp"),
                                   {Binding::UniformTexelBuffer, Binding::StorageTexelBuffer}, 4});
  Buffer in = device_buffer_with(ctx(), values, BufferUsage::UniformTexel, "texels in");
  Buffer out = Buffer::device(ctx(), 4 * (count + skip), BufferUsage::StorageTexel, "texels out");
  DescriptorSet set(pipeline, {in.texels(VK_FORMAT_R32G32B32A32_SFLOAT, 16 * skip),
                               out.texels(VK_FORMAT_R32_SFLOAT, 4 * skip)});
  ctx().run([&](Commands& cmd) {
    cmd.bind(pipeline, set);
    cmd.push(count);
    cmd.dispatch(groups_for(count, 64, ctx().limits()));
  });
  const std::vector<float> gpu = download_as<float>(ctx(), out, count + skip);
  for (uint32_t i = 0; i < count; ++i) {
    const float* v = &values[4 * size_t(i + skip)];
    const float sum = v[0] + v[1], product = sum * v[2], expected = product - v[3];
    ASSERT_EQ(gpu[i + skip], expected) << "texel " << i;
  }
}

TEST_F(ComputeTest, TexelBindingsWithoutAFormatOrUsageAreRefused) {
  ComputePipeline pipeline(ctx(), {gpu_test_shaders::get("texel_copy.comp"),
                                   {Binding::UniformTexelBuffer, Binding::StorageTexelBuffer}, 4});
  Buffer texels = Buffer::device(ctx(), 256, BufferUsage::UniformTexel | BufferUsage::StorageTexel, "texels");
  Buffer storage = Buffer::device(ctx(), 256, BufferUsage::Storage, "storage");
  const BufferRange vec4s{&texels, 0, VK_WHOLE_SIZE, VK_FORMAT_R32G32B32A32_SFLOAT};
  const BufferRange floats{&texels, 0, VK_WHOLE_SIZE, VK_FORMAT_R32_SFLOAT};
  EXPECT_NO_THROW(DescriptorSet(pipeline, {vec4s, floats}));
  EXPECT_THROW(DescriptorSet(pipeline, {texels.range(), floats}), std::invalid_argument);  // no format
  EXPECT_THROW(DescriptorSet(pipeline, {{&storage, 0, VK_WHOLE_SIZE, VK_FORMAT_R32G32B32A32_SFLOAT}, floats}),
               std::invalid_argument);  // not made for texels
  EXPECT_THROW(DescriptorSet(pipeline, {{&texels, 0, 40, VK_FORMAT_R32G32B32A32_SFLOAT}, floats}),
               std::invalid_argument);  // 40 bytes are not whole vec4 texels
}

TEST(EmbeddedShaders, LookupByFileName) {
  EXPECT_THROW(gpu_test_shaders::get("missing.comp"), std::out_of_range);
  EXPECT_EQ(gpu_test_shaders::all().size(), 10u);  // the test shaders listed in CMakeLists.txt
  EXPECT_EQ(gpu_test_shaders::get("mask3x3.comp").words[0], 0x07230203u);  // SPIR-V magic
}

}  // namespace
}  // namespace sdb::gpu
