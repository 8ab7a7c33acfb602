// A buffer just larger than one storage binding may cover, written chunk by chunk by a compute
// shader (one descriptor set and dispatch per chunk of plan_chunks) and read back whole.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "gpu_test_shaders.h"
#include "harness/gpu/gpu.h"
#include "harness/gpu/testing.h"

namespace sdb::gpu {
namespace {

class LargeBufferTest : public testing::VulkanTest {};

uint32_t pattern(uint32_t index) { return (index * 2654435761u) ^ 0x9E3779B9u; }

TEST_F(LargeBufferTest, OutputLargerThanOneBindingIsWrittenInChunks) {
  const DeviceLimits& limits = ctx().limits();
  // Past this, "just over the limit" costs too much memory and time for a unit test; such a
  // device (NVIDIA: 4 GiB) needs no split below that size anyway.
  constexpr uint64_t k_largest_tested = uint64_t(512) << 20;
  if (limits.max_storage_buffer_range > k_largest_tested)
    GTEST_SKIP() << ctx().info().name << " binds " << limits.max_storage_buffer_range
                 << " bytes at once; a split test would need more than 512 MiB";
  const uint64_t bytes = limits.max_storage_buffer_range + (uint64_t(64) << 10);
  const uint64_t elements = bytes / sizeof(uint32_t);
  const ChunkPlan plan = plan_chunks(limits, {elements, sizeof(uint32_t), 1, 64});
  ASSERT_EQ(plan.buffer_bytes.size(), 1u);
  ASSERT_GE(plan.chunks.size(), 2u);
  std::printf("%llu bytes in %zu chunks of at most %llu bytes on %s\n", static_cast<unsigned long long>(bytes),
              plan.chunks.size(), static_cast<unsigned long long>(plan.chunks.front().bytes), ctx().info().name.c_str());

  ComputePipeline pipeline(ctx(), {gpu_test_shaders::get("fill_pattern.comp"), {Binding::StorageBuffer}, 8});
  Buffer output = Buffer::device(ctx(), plan.buffer_bytes[0], BufferUsage::Storage, "large output");
  // One binding over the whole buffer is what the split avoids.
  EXPECT_THROW(DescriptorSet(pipeline, {output.range()}), std::invalid_argument);
  std::vector<DescriptorSet> sets;
  for (const Chunk& c : plan.chunks) sets.emplace_back(pipeline, std::vector{output.range(c.byte_offset, c.bytes)});
  Buffer staging = Buffer::readback(ctx(), output.size());
  ctx().run([&](Commands& cmd) {
    cmd.bind(pipeline);
    for (size_t i = 0; i < plan.chunks.size(); ++i) {
      const Chunk& c = plan.chunks[i];
      const uint32_t push[2] = {static_cast<uint32_t>(c.first_element), static_cast<uint32_t>(c.elements)};
      cmd.bind(sets[i]);
      cmd.push(push);
      cmd.dispatch(c.groups);
    }
    cmd.download(output, staging);
  });
  const std::vector<uint32_t> data = staging.read_as<uint32_t>(elements);
  uint64_t wrong = 0, first_wrong = 0;
  for (uint64_t i = 0; i < elements; ++i)
    if (data[i] != pattern(static_cast<uint32_t>(i)) && wrong++ == 0) first_wrong = i;
  EXPECT_EQ(wrong, 0u) << "first wrong element " << first_wrong;
}

TEST_F(LargeBufferTest, BufferPastTheLargestAllocationIsUnsupported) {
  const DeviceLimits& limits = ctx().limits();
  const uint64_t too_big = std::min(limits.max_memory_allocation_size, limits.max_buffer_size) + 1;
  EXPECT_THROW(Buffer::device(ctx(), too_big, BufferUsage::Storage, "too big"), Unsupported);
}

}  // namespace
}  // namespace sdb::gpu
