// Splitting a large output across bindings, dispatches and buffers, by the device's limits.
//
// One storage binding covers at most maxStorageBufferRange bytes (128 MiB on lavapipe, 4 GiB on
// NVIDIA), one buffer at most maxMemoryAllocationSize/maxBufferSize (2 GiB / 4 GiB on lavapipe),
// one dispatch at most maxComputeWorkGroupCount groups per dimension. plan_chunks() cuts an array
// of `elements` into chunks that respect all three; a scheme makes one descriptor set per chunk
// (binding the chunk's range) and one dispatch of chunk.groups per chunk, passing
// chunk.first_element in push constants. Example: the 22,465-face sword at N = 33 writes
// 22,465 x 33 x 33 float3 positions (294 MB): 3 chunks on lavapipe (granule 1089, one face), 1 on NVIDIA.
#pragma once

#include <cstdint>
#include <vector>

#include "harness/gpu/commands.h"
#include "harness/gpu/device_info.h"

namespace sdb::gpu {

struct ChunkRequest {
  uint64_t elements = 0;  // of the whole output
  uint32_t element_bytes = 0;  // 12 for a tightly packed float3
  uint64_t granule = 1;  // chunk boundaries fall on multiples of this many elements (a face's N*N vertices)
  uint32_t local_size = 64;  // invocations per work group, one element each: for Chunk::groups
  uint64_t max_chunk_bytes = 0;  // a smaller cap than the device's binding range; 0: none
};

struct Chunk {
  uint32_t buffer = 0;  // index into ChunkPlan::buffer_bytes
  uint64_t first_element = 0;  // in the whole output
  uint64_t elements = 0;
  uint64_t byte_offset = 0;  // in its buffer; a multiple of minStorageBufferOffsetAlignment
  uint64_t bytes = 0;  // at most maxStorageBufferRange
  Groups groups;  // covers `elements` invocations; see sdb/dispatch.glsl for the index
};

struct ChunkPlan {
  std::vector<uint64_t> buffer_bytes;  // more than one only past the device's largest buffer
  std::vector<Chunk> chunks;
};

// Throws std::invalid_argument when one granule alone exceeds a binding (or the request is empty).
ChunkPlan plan_chunks(const DeviceLimits& limits, const ChunkRequest& request);

// Work groups for `invocations` invocations of `local_size` each: x first up to the device's
// limit, then y, then z. Over-covers by less than one row of groups; shaders bound-check.
// Throws std::invalid_argument when the device cannot dispatch that many.
Groups groups_for(uint64_t invocations, uint32_t local_size, const DeviceLimits& limits);

// Invocations per work group for a kernel of long invocations (a row of samples, a fragment's
// entries) shaped for `gpu_size` on a GPU: on a CPU device (lavapipe) one subgroup, because it
// runs a work group's subgroups one after another and a subgroup whose invocations are all past
// the work (a dispatch's or a batch's end) still runs the whole shader, masked (README.md,
// "Memory access on lavapipe"); elsewhere `gpu_size` rounded up to whole subgroups. Measure before
// taking it: mipgh's one node an invocation ran 44% more instructions at 8 than at 64, and
// fragments' limit pass fewer instructions but more time.
uint32_t work_group_size(const DeviceInfo& device, uint32_t gpu_size);

}  // namespace sdb::gpu
