// Where a scheme's evaluation runs. Names are part of the CLI and results contract.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

namespace sdb {

// cpu: one thread (the harness runs it in a one-thread TBB arena); cpu-mt: all of TBB's threads;
// vulkan: the Vulkan device (lavapipe or a real GPU).
enum class Backend { Cpu, CpuMt, Vulkan };

std::string_view to_string(Backend b);
std::optional<Backend> parse_backend(std::string_view s);
const std::vector<Backend>& all_backends();

}  // namespace sdb
