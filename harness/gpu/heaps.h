// Whether a request's buffers fit the device's memory heaps, checked before anything is allocated
// (an allocation past a heap fails late, or on some drivers not at all until the device is lost).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "harness/gpu/buffer.h"
#include "harness/gpu/context.h"

namespace sdb::gpu {

// Bytes of a heap that holds device buffers and of one that holds readback buffers; the same heap
// counted once where they share one (lavapipe, integrated GPUs).
struct MemoryNeed {
  uint64_t device_bytes = 0;
  uint64_t readback_bytes = 0;
};

// Throws Unsupported naming `what` when the need exceeds what the device's heaps hold
// (heap_capacity). Each buffer is held to maxMemoryAllocationSize and maxBufferSize where it is
// made (Buffer); this is the sum.
void check_memory(const Context& ctx, const MemoryNeed& need, const std::string& what);

// Bytes a heap holds: the size the device reports, except on a CPU device (lavapipe), whose
// device memory is the process's own, allocated from the host as any other: there the host's
// `host_bytes` where they are more. Mesa 22.3's lavapipe reports a fixed 2 GiB
// (lvp_GetPhysicalDeviceMemoryProperties) and counts no allocation against it: 3 GiB in three
// buffers, and one of 2.5 GiB, allocate, fill and read back there
// (notes/2026-12-08-lavapipe-heap.md).
uint64_t heap_capacity(DeviceType type, uint64_t reported_bytes, uint64_t host_bytes);

// The host's physical memory in bytes (0 where unknown).
uint64_t host_memory_bytes();

// "1.25 GiB" (or "12.5 MiB" below 1 GiB), for such messages.
std::string gib_text(uint64_t bytes);

// Throws Unsupported naming `name` when `bytes` exceed one storage binding (maxStorageBufferRange).
void check_storage_binding(const Context& ctx, uint64_t bytes, std::string_view name);

// Throws Unsupported naming `name` when `texels` exceed one texel view (maxTexelBufferElements).
void check_texel_binding(const Context& ctx, uint64_t texels, std::string_view name);

// A UniformTexel device buffer holding `values` (one zero element when empty), uploaded blocking,
// checked to fit one texel view of one T per texel first.
template <class T>
Buffer texel_table(Context& ctx, std::vector<T> values, std::string_view name) {
  if (values.empty()) values.resize(1);
  check_texel_binding(ctx, values.size(), name);
  return device_buffer_with(ctx, values, BufferUsage::UniformTexel, name);
}

// A Storage device buffer holding `values` (one zero element when empty: Vulkan has no empty
// buffers), uploaded blocking, checked to fit one storage binding first.
template <class T>
Buffer storage_table(Context& ctx, std::vector<T> values, std::string_view name) {
  if (values.empty()) values.resize(1);
  check_storage_binding(ctx, values.size() * sizeof(T), name);
  return device_buffer_with(ctx, values, BufferUsage::Storage, name);
}

}  // namespace sdb::gpu
