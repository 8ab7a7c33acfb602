#include "harness/bench/paper_output.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "harness/gpu/device_info.h"

namespace sdb {

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string device_line() {
  const gpu::DeviceInfo info = gpu::probe();
  if (!info.available) return "no Vulkan device (" + info.reason + ")";
  std::string line = info.name + ", " + info.driver_name + " " + info.driver_info + ", Vulkan " + info.api_version;
  if (info.type == gpu::DeviceType::Cpu)
    line += ". This is a CPU implementation of Vulkan (Mesa's lavapipe: llvmpipe rasterizes on the CPU cores), "
            "so absolute frames per second are not comparable with the papers' GPUs; compare the shape across "
            "levels and meshes, and the ratios";
  return line;
}

std::string publish(const PaperTableOptions& options, const std::string& id, const std::string& markdown,
                    std::ostream& out) {
  std::filesystem::create_directories(options.out_dir);
  const std::string path = (std::filesystem::path(options.out_dir) / (id + ".md")).string();
  std::ofstream file(path);
  file << markdown;
  if (!file) throw std::runtime_error("cannot write " + path);
  out << markdown << "\nwrote " << path << "\n";
  return path;
}

}  // namespace sdb
