// Buffer: one VkBuffer with its own memory allocation (RAII, move-only).
//
//   Device    device-local; reached from the host through staging (upload()/download() below,
//             or Commands::upload/download inside a timed command buffer).
//   Upload    host-visible, persistently mapped; the host writes, the device reads (staging in).
//   Readback  host-visible, cached where the device offers it; the device writes, the host reads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <ranges>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "harness/gpu/context.h"

namespace sdb::gpu {

enum class MemoryKind { Device, Upload, Readback };

// What a buffer is bound as; transfer use (copy, fill) is always allowed.
enum class BufferUsage : uint32_t {
  None = 0,
  Storage = 1u << 0,
  Uniform = 1u << 1,
  Vertex = 1u << 2,
  Index = 1u << 3,
  Indirect = 1u << 4,
  UniformTexel = 1u << 5,
  StorageTexel = 1u << 6,
};
constexpr BufferUsage operator|(BufferUsage a, BufferUsage b) {
  return static_cast<BufferUsage>(static_cast<uint32_t>(a) | static_cast<uint32_t>(b));
}
constexpr bool has(BufferUsage set, BufferUsage flag) {
  return (static_cast<uint32_t>(set) & static_cast<uint32_t>(flag)) != 0;
}

class Buffer;

// A part of a buffer, for descriptor bindings. bytes == VK_WHOLE_SIZE: to the end.
struct BufferRange {
  const Buffer* buffer = nullptr;
  uint64_t offset = 0;
  uint64_t bytes = VK_WHOLE_SIZE;
  VkFormat texel_format = VK_FORMAT_UNDEFINED;  // texel-buffer bindings only: the view's format
};

class Buffer {
 public:
  Buffer() = default;
  // Throws std::invalid_argument for 0 bytes, Unsupported when `bytes` exceeds the device's
  // maxMemoryAllocationSize or maxBufferSize (split it: chunks.h), VulkanError otherwise.
  Buffer(Context& ctx, uint64_t bytes, BufferUsage usage, MemoryKind memory, std::string_view name);
  static Buffer device(Context& ctx, uint64_t bytes, BufferUsage usage, std::string_view name = "device buffer") {
    return Buffer(ctx, bytes, usage, MemoryKind::Device, name);
  }
  static Buffer upload(Context& ctx, uint64_t bytes, std::string_view name = "upload buffer") {
    return Buffer(ctx, bytes, BufferUsage::None, MemoryKind::Upload, name);
  }
  static Buffer readback(Context& ctx, uint64_t bytes, std::string_view name = "readback buffer") {
    return Buffer(ctx, bytes, BufferUsage::None, MemoryKind::Readback, name);
  }
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  VkBuffer handle() const { return buffer_; }
  uint64_t size() const { return size_; }
  MemoryKind memory() const { return memory_; }
  BufferUsage usage() const { return usage_; }
  const std::string& name() const { return name_; }
  explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }
  BufferRange range(uint64_t offset = 0, uint64_t bytes = VK_WHOLE_SIZE) const { return {this, offset, bytes}; }
  // The same range for a texel binding, viewed in `format`.
  BufferRange texels(VkFormat format, uint64_t offset = 0, uint64_t bytes = VK_WHOLE_SIZE) const {
    return {this, offset, bytes, format};
  }

  // Host access to Upload and Readback buffers (std::logic_error for Device ones). Like the
  // commands that write a buffer, they are const: they change its contents, not the handle.
  // write() flushes and read() invalidates when the memory is not host-coherent.
  void write(const void* data, uint64_t bytes, uint64_t offset = 0) const;
  void read(void* data, uint64_t bytes, uint64_t offset = 0) const;
  template <std::ranges::contiguous_range R>
  void write(const R& values, uint64_t offset = 0) const {
    static_assert(std::is_trivially_copyable_v<std::ranges::range_value_t<R>>);
    write(std::ranges::data(values), std::ranges::size(values) * sizeof(std::ranges::range_value_t<R>), offset);
  }
  template <class T>
  std::vector<T> read_as(uint64_t count, uint64_t offset = 0) const {
    static_assert(std::is_trivially_copyable_v<T>);
    std::vector<T> out(count);
    read(out.data(), count * sizeof(T), offset);
    return out;
  }

 private:
  void release();
  std::byte* host_pointer(uint64_t bytes, uint64_t offset, const char* what) const;

  Context* ctx_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_handle_ = VK_NULL_HANDLE;
  std::byte* mapped_ = nullptr;
  bool coherent_ = true;
  uint64_t size_ = 0;
  MemoryKind memory_ = MemoryKind::Device;
  BufferUsage usage_ = BufferUsage::None;
  std::string name_;
};

// Blocking transfers for setup and tests (outside timed work): through a temporary staging
// buffer for Device buffers, directly for host-visible ones.
void upload(Context& ctx, const Buffer& dst, const void* data, uint64_t bytes, uint64_t offset = 0);
void download(Context& ctx, const Buffer& src, void* data, uint64_t bytes, uint64_t offset = 0);

template <std::ranges::contiguous_range R>
void upload(Context& ctx, const Buffer& dst, const R& values, uint64_t offset = 0) {
  static_assert(std::is_trivially_copyable_v<std::ranges::range_value_t<R>>);
  upload(ctx, dst, std::ranges::data(values), std::ranges::size(values) * sizeof(std::ranges::range_value_t<R>),
         offset);
}

template <class T>
std::vector<T> download_as(Context& ctx, const Buffer& src, uint64_t count, uint64_t offset = 0) {
  static_assert(std::is_trivially_copyable_v<T>);
  std::vector<T> out(count);
  download(ctx, src, out.data(), count * sizeof(T), offset);
  return out;
}

// A device buffer holding `values` (a vector, span or array; uploaded, blocking).
template <std::ranges::contiguous_range R>
Buffer device_buffer_with(Context& ctx, const R& values, BufferUsage usage, std::string_view name) {
  Buffer buffer =
      Buffer::device(ctx, std::ranges::size(values) * sizeof(std::ranges::range_value_t<R>), usage, name);
  upload(ctx, buffer, values);
  return buffer;
}

}  // namespace sdb::gpu
