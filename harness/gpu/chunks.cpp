#include "harness/gpu/chunks.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace sdb::gpu {

namespace {
uint64_t ceil_div(uint64_t a, uint64_t b) { return (a + b - 1) / b; }
}  // namespace

uint32_t work_group_size(const DeviceInfo& device, uint32_t gpu_size) {
  const uint32_t subgroup = std::max<uint32_t>(1, device.limits.subgroup_size);
  if (device.type == DeviceType::Cpu) return subgroup;
  return std::max<uint32_t>(1, (gpu_size + subgroup - 1) / subgroup) * subgroup;
}

Groups groups_for(uint64_t invocations, uint32_t local_size, const DeviceLimits& limits) {
  if (local_size == 0) throw std::invalid_argument("groups_for: local_size 0");
  const uint64_t groups = ceil_div(invocations, local_size);
  if (groups == 0) return {0, 1, 1};
  const auto& max = limits.max_compute_work_group_count;
  const uint64_t x = std::min<uint64_t>(groups, max[0]);
  const uint64_t rows = ceil_div(groups, x);
  const uint64_t y = std::min<uint64_t>(rows, max[1]);
  const uint64_t z = ceil_div(rows, y);
  if (x == 0 || y == 0 || z > max[2])
    throw std::invalid_argument(std::to_string(invocations) + " invocations exceed what the device can dispatch at once");
  return {static_cast<uint32_t>(x), static_cast<uint32_t>(y), static_cast<uint32_t>(z)};
}

ChunkPlan plan_chunks(const DeviceLimits& limits, const ChunkRequest& request) {
  if (request.elements == 0 || request.element_bytes == 0 || request.granule == 0)
    throw std::invalid_argument("plan_chunks: elements, element_bytes and granule must be positive");
  const uint64_t eb = request.element_bytes;
  // Chunk sizes are multiples of `step` elements, so every chunk starts on a granule and on an
  // offset the device can bind.
  // Storage and texel views of a chunk both start at its offset.
  const uint64_t alignment = std::lcm(std::max<uint64_t>(1, limits.min_storage_buffer_offset_alignment),
                                      std::max<uint64_t>(1, limits.min_texel_buffer_offset_alignment));
  const uint64_t align_elements = alignment / std::gcd(alignment, eb);
  const uint64_t step = std::lcm(request.granule, align_elements);
  const uint64_t max_buffer = std::min(limits.max_memory_allocation_size, limits.max_buffer_size);
  uint64_t max_bytes = std::min(limits.max_storage_buffer_range, max_buffer);
  if (request.max_chunk_bytes > 0) max_bytes = std::min(max_bytes, request.max_chunk_bytes);
  const uint64_t chunk_elements = max_bytes / (step * eb) * step;
  if (chunk_elements == 0)
    throw std::invalid_argument("plan_chunks: one granule of " + std::to_string(step * eb) +
                                " bytes exceeds a binding of " + std::to_string(max_bytes) + " bytes");
  const uint64_t chunks_per_buffer = std::max<uint64_t>(1, max_buffer / (chunk_elements * eb));

  ChunkPlan plan;
  for (uint64_t first = 0, index = 0; first < request.elements; first += chunk_elements, ++index) {
    Chunk c;
    c.buffer = static_cast<uint32_t>(index / chunks_per_buffer);
    c.first_element = first;
    c.elements = std::min(chunk_elements, request.elements - first);
    c.byte_offset = (index % chunks_per_buffer) * chunk_elements * eb;
    c.bytes = c.elements * eb;
    c.groups = groups_for(c.elements, request.local_size, limits);
    if (c.buffer >= plan.buffer_bytes.size()) plan.buffer_bytes.push_back(0);
    plan.buffer_bytes[c.buffer] = c.byte_offset + c.bytes;
    plan.chunks.push_back(c);
  }
  return plan;
}

}  // namespace sdb::gpu
