// plan_chunks and groups_for against given limits; no device needed.
#include <gtest/gtest.h>

#include "harness/gpu/chunks.h"

namespace sdb::gpu {
namespace {

DeviceLimits lavapipe_limits() {  // Mesa 22.3 lavapipe, as vulkaninfo reports it
  DeviceLimits l;
  l.max_storage_buffer_range = uint64_t(128) << 20;
  l.max_memory_allocation_size = uint64_t(2) << 30;
  l.max_buffer_size = 0xffffffffu;
  l.min_storage_buffer_offset_alignment = 16;
  l.max_compute_work_group_count = {65535, 65535, 65535};
  return l;
}

DeviceLimits nvidia_like_limits() {
  DeviceLimits l = lavapipe_limits();
  l.max_storage_buffer_range = 0xffffffffu;
  l.max_memory_allocation_size = l.max_buffer_size = uint64_t(64) << 30;
  l.max_compute_work_group_count = {0x7fffffffu, 65535, 65535};
  return l;
}

void expect_valid(const ChunkPlan& plan, const DeviceLimits& l, const ChunkRequest& r) {
  uint64_t next = 0;
  for (const Chunk& c : plan.chunks) {
    EXPECT_EQ(c.first_element, next);
    EXPECT_LE(c.bytes, l.max_storage_buffer_range);
    EXPECT_EQ(c.byte_offset % l.min_storage_buffer_offset_alignment, 0u);
    EXPECT_EQ(c.bytes, c.elements * r.element_bytes);
    EXPECT_LE(c.byte_offset + c.bytes, plan.buffer_bytes.at(c.buffer));
    if (&c != &plan.chunks.back()) {
      EXPECT_EQ(c.elements % r.granule, 0u);
    }
    EXPECT_GE(uint64_t(c.groups.x) * c.groups.y * c.groups.z * r.local_size, c.elements);
    EXPECT_LE(c.groups.x, l.max_compute_work_group_count[0]);
    EXPECT_LE(c.groups.y, l.max_compute_work_group_count[1]);
    next += c.elements;
  }
  EXPECT_EQ(next, r.elements);
  for (uint64_t b : plan.buffer_bytes) EXPECT_LE(b, std::min(l.max_memory_allocation_size, l.max_buffer_size));
}

// The 22,465-quad sword at N = 33: float3 positions (294 MB; normals are another such buffer).
const ChunkRequest k_sword{uint64_t(22465) * 33 * 33, 12, 33 * 33, 64};

TEST(PlanChunks, SwordAtN33OnLavapipeTakesThreeBindings) {
  const DeviceLimits l = lavapipe_limits();
  const ChunkPlan plan = plan_chunks(l, k_sword);
  EXPECT_EQ(plan.buffer_bytes.size(), 1u);
  EXPECT_EQ(plan.chunks.size(), 3u);
  expect_valid(plan, l, k_sword);
}

TEST(PlanChunks, SwordAtN33OnNvidiaTakesOne) {
  const DeviceLimits l = nvidia_like_limits();
  const ChunkPlan plan = plan_chunks(l, k_sword);
  ASSERT_EQ(plan.chunks.size(), 1u);
  EXPECT_EQ(plan.chunks[0].groups.x, (k_sword.elements + 63) / 64);
  expect_valid(plan, l, k_sword);
}

TEST(PlanChunks, SplitsAcrossBuffersPastTheLargestAllocation) {
  const DeviceLimits l = lavapipe_limits();
  const ChunkRequest r{uint64_t(5) << 30, 1, 1, 256};  // 5 GiB of bytes
  const ChunkPlan plan = plan_chunks(l, r);
  EXPECT_EQ(plan.buffer_bytes.size(), 3u);
  expect_valid(plan, l, r);
}

TEST(PlanChunks, ChunksEndOnGranulesAndAlignedOffsets) {
  DeviceLimits l = lavapipe_limits();
  l.min_storage_buffer_offset_alignment = 256;
  const ChunkRequest r{1000003, 12, 7, 32, 100000};
  const ChunkPlan plan = plan_chunks(l, r);
  EXPECT_GT(plan.chunks.size(), 100u);
  expect_valid(plan, l, r);
}

TEST(PlanChunks, RefusesAGranuleLargerThanABinding) {
  const DeviceLimits l = lavapipe_limits();
  EXPECT_THROW(plan_chunks(l, {100, 12, 100, 64, 1000}), std::invalid_argument);
  EXPECT_THROW(plan_chunks(l, {0, 12}), std::invalid_argument);
}

TEST(GroupsFor, FillsXThenY) {
  const DeviceLimits l = lavapipe_limits();
  const Groups small = groups_for(1000, 64, l);
  EXPECT_EQ(small.x, 16u);
  EXPECT_EQ(small.y, 1u);
  const Groups big = groups_for(uint64_t(65535) * 64 * 3 + 1, 64, l);
  EXPECT_EQ(big.x, 65535u);
  EXPECT_EQ(big.y, 4u);
  EXPECT_EQ(big.z, 1u);
}

}  // namespace
}  // namespace sdb::gpu
