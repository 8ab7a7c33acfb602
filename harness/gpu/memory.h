// Internal: memory type choice for buffers and images.
#pragma once

#include <cstdint>

#include "harness/gpu/buffer.h"
#include "harness/gpu/vk_functions.h"

namespace sdb::gpu {

// The allowed memory type (bit i of `allowed`) best suited to `kind`, or -1 when none fits.
int choose_memory_type(const VkPhysicalDeviceMemoryProperties& props, uint32_t allowed, MemoryKind kind);

}  // namespace sdb::gpu
