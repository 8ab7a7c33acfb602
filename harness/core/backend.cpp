#include "harness/core/backend.h"

namespace sdb {

std::string_view to_string(Backend b) {
  switch (b) {
    case Backend::Cpu: return "cpu";
    case Backend::CpuMt: return "cpu-mt";
    case Backend::Vulkan: return "vulkan";
    case Backend::OpenGl: return "opengl";
  }
  return "?";
}

const std::vector<Backend>& all_backends() {
  static const std::vector<Backend> all = {Backend::Cpu, Backend::CpuMt, Backend::Vulkan, Backend::OpenGl};
  return all;
}

const std::string& backend_names() {
  static const std::string names = [] {
    std::string s;
    for (Backend b : all_backends()) s += (s.empty() ? "" : ", ") + std::string(to_string(b));
    return s;
  }();
  return names;
}

bool is_gpu(Backend b) { return b == Backend::Vulkan || b == Backend::OpenGl; }

std::optional<Backend> parse_backend(std::string_view s) {
  for (Backend b : all_backends())
    if (s == to_string(b)) return b;
  return std::nullopt;
}

}  // namespace sdb
