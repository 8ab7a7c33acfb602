// Child processes started with an argument vector (posix_spawn), never through a shell: data
// (mesh names, paths) can never become a command.
#pragma once

#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

namespace sdb {

struct ProcessOptions {
  bool quiet = false;  // stdout and stderr to /dev/null
  std::string output_file;  // when set (and not quiet): stdout and stderr appended to this file
  // > 0: a child still running after this many seconds is sent SIGTERM, and SIGKILL 5 s later.
  double timeout_s = 0;
};

struct ProcessResult {
  int exit_code = -1;  // -1 when it did not exit normally
  int signal = 0;      // the signal that ended it, or 0
  bool timed_out = false;  // ended by ProcessOptions::timeout_s
  // "exit code 1", "killed by signal 11 (SIGSEGV, Segmentation fault)"
  std::string describe() const;
};

// Runs argv[0] (searched on PATH when it has no '/') with argv and waits for it. Throws
// std::runtime_error when it cannot be started.
ProcessResult run_process(const std::vector<std::string>& argv, const ProcessOptions& options = {});

// A child process started with an argument vector and a two-way channel on its descriptor
// `channel_fd` (a socket pair): lines go both ways. A child still running when this is destroyed
// is killed (SIGKILL) and reaped.
class ChannelProcess {
 public:
  // Throws std::runtime_error when it cannot be started.
  ChannelProcess(const std::vector<std::string>& argv, int channel_fd);
  ~ChannelProcess();
  ChannelProcess(const ChannelProcess&) = delete;
  ChannelProcess& operator=(const ChannelProcess&) = delete;

  // Sends `line` and a newline; false when the child has closed its end (it ended).
  bool send_line(const std::string& line);
  // The next complete line; nullopt once the child has closed its end (a last line cut short by
  // its death is dropped).
  std::optional<std::string> read_line();
  // Closes this end (a child reading it sees the end) and waits for the child.
  ProcessResult wait();

 private:
  std::string name_;
  pid_t pid_ = -1;
  int fd_ = -1;
  std::string pending_;  // read, not yet a complete line
};

// The path of the running executable (/proc/self/exe).
std::string self_executable();

}  // namespace sdb
