// Where a scheme's evaluation runs. Names are part of the CLI and results contract.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sdb {

// cpu: one thread (the harness runs it in a one-thread TBB arena); cpu-mt: all of TBB's threads;
// vulkan: the Vulkan device (lavapipe or a real GPU); opengl: a headless OpenGL 4.3 context on
// the same kind of device (Mesa's llvmpipe or the vendor's driver), for OpenSubdiv's GL peer.
enum class Backend { Cpu, CpuMt, Vulkan, OpenGl };

std::string_view to_string(Backend b);
std::optional<Backend> parse_backend(std::string_view s);
const std::vector<Backend>& all_backends();
// "cpu, cpu-mt, vulkan, opengl", for messages.
const std::string& backend_names();
// Backends whose rows are timed by the device's timestamps (vulkan, opengl).
bool is_gpu(Backend b);

}  // namespace sdb
