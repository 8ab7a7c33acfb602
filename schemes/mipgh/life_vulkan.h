// The game of life (life.h) on a Vulkan device: the states in two device buffers, one dispatch of
// shaders/life.comp per generation over the neighbour lists the cpu processor gathered.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

namespace sdb::mipgh {

class VulkanLife {
 public:
  // `first`: per node the start of its list in `neighbours` (nodes + 1 entries). Throws
  // Unsupported without a device.
  VulkanLife(const std::vector<uint32_t>& first, const std::vector<uint32_t>& neighbours);
  ~VulkanLife();
  void upload(const std::vector<float>& state);
  void step();
  std::vector<float> download();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sdb::mipgh
