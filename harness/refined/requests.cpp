#include "harness/refined/requests.h"

#include "harness/gpu/gpu.h"

namespace sdb::refined {

std::optional<std::string> vulkan_unavailable() {
  static const gpu::DeviceInfo device = gpu::probe();
  if (!device.available) return "no Vulkan device: " + device.reason;
  return std::nullopt;
}

std::optional<std::string> unsupported_request(const RunRequest& r, const std::string& scheme) {
  if (r.level < 1 || r.level > kMaxDepth) return "depth must be 1.." + std::to_string(kMaxDepth);
  if (r.backend == Backend::Vulkan) return vulkan_unavailable();
  if (r.backend != Backend::Cpu && r.backend != Backend::CpuMt) return scheme + " runs on cpu, cpu-mt and vulkan";
  return std::nullopt;
}

}  // namespace sdb::refined
