// Child processes started with an argument vector (posix_spawn), never through a shell: data
// (mesh names, paths) can never become a command.
#pragma once

#include <string>
#include <vector>

namespace sdb {

struct ProcessOptions {
  bool quiet = false;  // stdout and stderr to /dev/null
};

struct ProcessResult {
  int exit_code = -1;  // -1 when it did not exit normally
  int signal = 0;      // the signal that ended it, or 0
  std::string describe() const;  // "exit code 1", "killed by signal 11 (Segmentation fault)"
};

// Runs argv[0] (searched on PATH when it has no '/') with argv and waits for it. Throws
// std::runtime_error when it cannot be started.
ProcessResult run_process(const std::vector<std::string>& argv, const ProcessOptions& options = {});

// The path of the running executable (/proc/self/exe).
std::string self_executable();

}  // namespace sdb
