// A buffer just larger than one storage binding may cover, written chunk by chunk by a compute
// shader (one descriptor set and dispatch per chunk of plan_chunks) and read back whole; and more
// than a CPU device's reported heap in two buffers (heaps.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
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


TEST(HeapCapacity, ACpuDeviceHoldsTheHostsMemoryOthersTheirHeap) {
  constexpr uint64_t GiB = uint64_t(1) << 30;
  EXPECT_EQ(heap_capacity(DeviceType::Cpu, 2 * GiB, 24 * GiB), 24 * GiB);  // lavapipe's fixed 2 GiB
  EXPECT_EQ(heap_capacity(DeviceType::Cpu, 8 * GiB, 4 * GiB), 8 * GiB);
  EXPECT_EQ(heap_capacity(DeviceType::Discrete, 8 * GiB, 64 * GiB), 8 * GiB);
  EXPECT_EQ(heap_capacity(DeviceType::Integrated, 2 * GiB, 64 * GiB), 2 * GiB);
}

// lavapipe's reported heap (2 GiB in Mesa 22.3) is no limit: device memory is the process's own.
// Two buffers of more than the heap together are allocated, filled and read back at both ends,
// each within maxMemoryAllocationSize; check_memory admits them and refuses past the host's memory.
TEST_F(LargeBufferTest, MoreThanTheReportedHeapIsAllocatedOnACpuDevice) {
  if (ctx().info().type != DeviceType::Cpu)
    GTEST_SKIP() << ctx().info().name << " is no CPU device: its heap is the limit it reports";
  const VkPhysicalDeviceMemoryProperties& p = ctx().memory_properties();
  const uint64_t heap = p.memoryHeaps[p.memoryTypes[0].heapIndex].size;
  constexpr uint64_t k_largest_tested = uint64_t(4) << 30;
  if (heap > k_largest_tested) GTEST_SKIP() << "a heap of " << gib_text(heap) << " is more than a unit test allocates";
  const uint64_t each = (heap / 2 + (uint64_t(64) << 20)) & ~uint64_t(4095);
  ASSERT_LE(each, std::min(ctx().limits().max_memory_allocation_size, ctx().limits().max_buffer_size));
  ASSERT_GT(2 * each, heap);
  EXPECT_NO_THROW(check_memory(ctx(), {2 * each, 0}, "two buffers"));
  try {
    check_memory(ctx(), {host_memory_bytes() + 1, 0}, "past the host");
    ADD_FAILURE() << "a need past the host's memory was admitted";
  } catch (const Unsupported& e) {
    EXPECT_NE(std::string(e.what()).find("is not a limit the driver keeps"), std::string::npos) << e.what();
  }
  std::vector<Buffer> buffers;
  for (int i = 0; i < 2; ++i) buffers.push_back(Buffer::device(ctx(), each, BufferUsage::Storage, "half and more of the heap"));
  constexpr uint64_t k_end = 4096;
  Buffer staging = Buffer::readback(ctx(), 4 * k_end);
  ctx().run([&](Commands& cmd) {
    for (uint32_t i = 0; i < 2; ++i) cmd.fill(buffers[i], 0xA5A50000u + i);
    for (uint32_t i = 0; i < 2; ++i) {
      cmd.download(buffers[i], staging, k_end, 0, 2 * i * k_end);
      cmd.download(buffers[i], staging, k_end, each - k_end, (2 * i + 1) * k_end);
    }
  });
  const std::vector<uint32_t> words = staging.read_as<uint32_t>(4 * k_end / 4);
  uint64_t wrong = 0;
  for (size_t w = 0; w < words.size(); ++w) wrong += words[w] != 0xA5A50000u + uint32_t(w / (2 * k_end / 4));
  EXPECT_EQ(wrong, 0u);
  std::printf("%s: 2 buffers of %s (%s in all) past its reported heap of %s\n", ctx().info().name.c_str(),
              gib_text(each).c_str(), gib_text(2 * each).c_str(), gib_text(heap).c_str());
}

}  // namespace
}  // namespace sdb::gpu
