#include "harness/gpu/heaps.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "harness/gpu/errors.h"

namespace sdb::gpu {
namespace {

// Heap of the first memory type with all of `flags`, or -1.
int heap_with(const VkPhysicalDeviceMemoryProperties& p, VkMemoryPropertyFlags flags) {
  for (uint32_t t = 0; t < p.memoryTypeCount; ++t)
    if ((p.memoryTypes[t].propertyFlags & flags) == flags) return static_cast<int>(p.memoryTypes[t].heapIndex);
  return -1;
}

}  // namespace

std::string gib_text(uint64_t bytes) {
  char text[32];
  if (bytes < (1ull << 30)) std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / double(1ull << 20));
  else std::snprintf(text, sizeof text, "%.2f GiB", double(bytes) / double(1ull << 30));
  return text;
}

void check_storage_binding(const Context& ctx, uint64_t bytes, std::string_view name) {
  if (bytes > ctx.limits().max_storage_buffer_range)
    throw Unsupported("'" + std::string(name) + "' of " + gib_text(bytes) + " exceeds one storage binding on " +
                      ctx.info().name + " (" + gib_text(ctx.limits().max_storage_buffer_range) + ")");
}

void check_texel_binding(const Context& ctx, uint64_t texels, std::string_view name) {
  if (texels > ctx.limits().max_texel_buffer_elements)
    throw Unsupported("'" + std::string(name) + "' of " + std::to_string(texels) + " texels exceeds one texel view on " +
                      ctx.info().name + " (" + std::to_string(ctx.limits().max_texel_buffer_elements) + ")");
}

uint64_t heap_capacity(DeviceType type, uint64_t reported_bytes, uint64_t host_bytes) {
  return type == DeviceType::Cpu ? std::max(reported_bytes, host_bytes) : reported_bytes;
}

uint64_t host_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) : 0;
}

void check_memory(const Context& ctx, const MemoryNeed& need, const std::string& what) {
  const VkPhysicalDeviceMemoryProperties& p = ctx.memory_properties();
  const int device_heap = heap_with(p, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  int readback_heap = heap_with(p, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
  if (readback_heap < 0) readback_heap = heap_with(p, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT);
  const uint64_t host = host_memory_bytes();
  auto capacity = [&](int heap) { return heap_capacity(ctx.info().type, p.memoryHeaps[heap].size, host); };
  auto refuse = [&](uint64_t needed, int heap, const char* kind) {
    const uint64_t reported = p.memoryHeaps[heap].size;
    const std::string has = capacity(heap) == reported
                                ? " has a heap of " + gib_text(reported)
                                : "'s memory is this machine's, " + gib_text(capacity(heap)) + " (its reported heap of " +
                                      gib_text(reported) + " is not a limit the driver keeps)";
    throw Unsupported(what + " needs " + gib_text(needed) + " of " + kind + " memory; " + ctx.info().name + has);
  };
  if (device_heap >= 0 && device_heap == readback_heap) {
    const uint64_t total = need.device_bytes + need.readback_bytes;
    if (total > capacity(device_heap)) refuse(total, device_heap, "device and readback");
    return;
  }
  if (device_heap >= 0 && need.device_bytes > capacity(device_heap)) refuse(need.device_bytes, device_heap, "device");
  if (readback_heap >= 0 && need.readback_bytes > capacity(readback_heap))
    refuse(need.readback_bytes, readback_heap, "readback");
}

}  // namespace sdb::gpu
