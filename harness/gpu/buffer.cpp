#include "harness/gpu/buffer.h"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "harness/gpu/commands.h"
#include "harness/gpu/errors.h"
#include "harness/gpu/memory.h"

namespace sdb::gpu {

namespace {

std::string mib(uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / double(1 << 20));
  return text;
}

VkBufferUsageFlags vk_usage(BufferUsage usage) {
  VkBufferUsageFlags flags = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  if (has(usage, BufferUsage::Storage)) flags |= VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  if (has(usage, BufferUsage::Uniform)) flags |= VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
  if (has(usage, BufferUsage::Vertex)) flags |= VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
  if (has(usage, BufferUsage::Index)) flags |= VK_BUFFER_USAGE_INDEX_BUFFER_BIT;
  if (has(usage, BufferUsage::Indirect)) flags |= VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
  if (has(usage, BufferUsage::UniformTexel)) flags |= VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
  if (has(usage, BufferUsage::StorageTexel)) flags |= VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT;
  return flags;
}

struct MemoryWish {
  VkMemoryPropertyFlags required, preferred, avoided;
};

// Staging memory stays out of device-local host-visible memory where the device has other
// host memory: on discrete GPUs that is the small BAR window, better left to others.
MemoryWish wish_for(MemoryKind kind) {
  switch (kind) {
    case MemoryKind::Device:
      return {VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT};
    case MemoryKind::Upload:
      return {VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, 0,
              VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT};
    case MemoryKind::Readback:
      return {VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT,
              VK_MEMORY_PROPERTY_HOST_CACHED_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
              VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT};
  }
  return {0, 0, 0};
}

}  // namespace

// The allowed memory type with the required flags, the most preferred and the fewest avoided
// flags; -1 when none has the required flags.
int choose_memory_type(const VkPhysicalDeviceMemoryProperties& props, uint32_t allowed, MemoryKind kind) {
  const MemoryWish wish = wish_for(kind);
  int best = -1, best_score = 0;
  for (uint32_t i = 0; i < props.memoryTypeCount; ++i) {
    const VkMemoryPropertyFlags f = props.memoryTypes[i].propertyFlags;
    if (!(allowed & (1u << i)) || (f & wish.required) != wish.required) continue;
    const int score = 2 * std::popcount(f & wish.preferred) - 4 * std::popcount(f & wish.avoided);
    if (best < 0 || score > best_score) {
      best = static_cast<int>(i);
      best_score = score;
    }
  }
  return best;
}

Buffer::Buffer(Context& ctx, uint64_t bytes, BufferUsage usage, MemoryKind memory, std::string_view name)
    : ctx_(&ctx), size_(bytes), memory_(memory), usage_(usage), name_(name) {
  if (bytes == 0) throw std::invalid_argument("buffer '" + name_ + "' of 0 bytes");
  const DeviceLimits& limits = ctx.limits();
  const uint64_t max_bytes = std::min(limits.max_memory_allocation_size, limits.max_buffer_size);
  if (bytes > max_bytes)
    throw Unsupported("buffer '" + name_ + "' of " + mib(bytes) + " exceeds the largest buffer of " + ctx.info().name +
                      " (" + mib(max_bytes) + "); split it across buffers (chunks.h)");
  const Vk& vk = ctx.vk();
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = bytes;
  info.usage = vk_usage(usage);
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  const std::string doing = "creating buffer '" + name_ + "' of " + mib(bytes);
  check(vk.vkCreateBuffer(ctx.device(), &info, nullptr, &buffer_), "vkCreateBuffer", doing);
  try {
    VkMemoryRequirements reqs;
    vk.vkGetBufferMemoryRequirements(ctx.device(), buffer_, &reqs);
    const VkPhysicalDeviceMemoryProperties& props = ctx.memory_properties();
    const int type = choose_memory_type(props, reqs.memoryTypeBits, memory);
    if (type < 0) throw Unsupported(ctx.info().name + " has no memory type for " + doing);
    const VkMemoryPropertyFlags flags = props.memoryTypes[type].propertyFlags;
    coherent_ = (flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) != 0;
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = reqs.size;
    alloc.memoryTypeIndex = static_cast<uint32_t>(type);
    check(vk.vkAllocateMemory(ctx.device(), &alloc, nullptr, &memory_handle_), "vkAllocateMemory", doing);
    check(vk.vkBindBufferMemory(ctx.device(), buffer_, memory_handle_, 0), "vkBindBufferMemory", doing);
    if (memory != MemoryKind::Device) {
      void* p = nullptr;
      check(vk.vkMapMemory(ctx.device(), memory_handle_, 0, VK_WHOLE_SIZE, 0, &p), "vkMapMemory", doing);
      mapped_ = static_cast<std::byte*>(p);
    }
  } catch (...) {
    release();
    throw;
  }
}

Buffer::~Buffer() { release(); }

Buffer::Buffer(Buffer&& other) noexcept { *this = std::move(other); }

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    release();
    ctx_ = std::exchange(other.ctx_, nullptr);
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    memory_handle_ = std::exchange(other.memory_handle_, VK_NULL_HANDLE);
    mapped_ = std::exchange(other.mapped_, nullptr);
    coherent_ = other.coherent_;
    size_ = std::exchange(other.size_, 0);
    memory_ = other.memory_;
    usage_ = other.usage_;
    name_ = std::move(other.name_);
  }
  return *this;
}

void Buffer::release() {
  if (!ctx_) return;
  const Vk& vk = ctx_->vk();
  if (mapped_) vk.vkUnmapMemory(ctx_->device(), memory_handle_);
  if (buffer_) vk.vkDestroyBuffer(ctx_->device(), buffer_, nullptr);
  if (memory_handle_) vk.vkFreeMemory(ctx_->device(), memory_handle_, nullptr);
  mapped_ = nullptr;
  buffer_ = VK_NULL_HANDLE;
  memory_handle_ = VK_NULL_HANDLE;
  ctx_ = nullptr;
}

std::byte* Buffer::host_pointer(uint64_t bytes, uint64_t offset, const char* what) const {
  if (!mapped_) throw std::logic_error(std::string(what) + " on device-local buffer '" + name_ + "'; use staging");
  if (offset > size_ || bytes > size_ - offset)
    throw std::out_of_range(std::string(what) + " of " + std::to_string(bytes) + " bytes at " + std::to_string(offset) +
                            " past the end of buffer '" + name_ + "' (" + std::to_string(size_) + " bytes)");
  return mapped_ + offset;
}

void Buffer::write(const void* data, uint64_t bytes, uint64_t offset) const {
  std::memcpy(host_pointer(bytes, offset, "write"), data, bytes);
  if (!coherent_) {
    VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, nullptr, memory_handle_, 0, VK_WHOLE_SIZE};
    check(ctx_->vk().vkFlushMappedMemoryRanges(ctx_->device(), 1, &range), "vkFlushMappedMemoryRanges",
          "writing buffer '" + name_ + "'");
  }
}

void Buffer::read(void* data, uint64_t bytes, uint64_t offset) const {
  const std::byte* src = host_pointer(bytes, offset, "read");
  if (!coherent_) {
    VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, nullptr, memory_handle_, 0, VK_WHOLE_SIZE};
    check(ctx_->vk().vkInvalidateMappedMemoryRanges(ctx_->device(), 1, &range), "vkInvalidateMappedMemoryRanges",
          "reading buffer '" + name_ + "'");
  }
  std::memcpy(data, src, bytes);
}

void upload(Context& ctx, const Buffer& dst, const void* data, uint64_t bytes, uint64_t offset) {
  if (bytes == 0) return;
  if (dst.memory() != MemoryKind::Device) {
    dst.write(data, bytes, offset);
    return;
  }
  Buffer staging = Buffer::upload(ctx, bytes, "staging for " + dst.name());
  staging.write(data, bytes);
  ctx.run([&](Commands& cmd) { cmd.upload(staging, dst, bytes, 0, offset); });
}

void download(Context& ctx, const Buffer& src, void* data, uint64_t bytes, uint64_t offset) {
  if (bytes == 0) return;
  if (src.memory() != MemoryKind::Device) {
    src.read(data, bytes, offset);
    return;
  }
  Buffer staging = Buffer::readback(ctx, bytes, "staging for " + src.name());
  ctx.run([&](Commands& cmd) { cmd.download(src, staging, bytes, offset, 0); });
  staging.read(data, bytes);
}

}  // namespace sdb::gpu
