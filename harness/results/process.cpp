#include "harness/results/process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/socket.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <thread>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

extern char** environ;

namespace sdb {
namespace {

struct SpawnActions {
  posix_spawn_file_actions_t actions;
  SpawnActions() { posix_spawn_file_actions_init(&actions); }
  ~SpawnActions() { posix_spawn_file_actions_destroy(&actions); }
  SpawnActions(const SpawnActions&) = delete;
  SpawnActions& operator=(const SpawnActions&) = delete;
};

pid_t spawn(const std::vector<std::string>& argv, const SpawnActions& actions) {
  if (argv.empty()) throw std::logic_error("run_process: empty argument vector");
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int err = posix_spawnp(&pid, args[0], &actions.actions, nullptr, args.data(), environ);
  if (err != 0) throw std::runtime_error("cannot start " + argv[0] + ": " + std::strerror(err));
  return pid;
}

ProcessResult result_of(int status) {
  ProcessResult r;
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  return r;
}

ProcessResult wait_for(pid_t pid, const std::string& name) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw std::runtime_error("waiting for " + name + ": " + std::strerror(errno));
  return result_of(status);
}

// Waits, polling, and ends the child once `timeout_s` has passed: SIGTERM (it may still write what
// it has), then SIGKILL after a grace period.
ProcessResult wait_for(pid_t pid, const std::string& name, double timeout_s) {
  using clock = std::chrono::steady_clock;
  const auto term_at = clock::now() + std::chrono::duration<double>(timeout_s);
  const auto kill_at = term_at + std::chrono::seconds(5);
  bool termed = false, killed = false;
  for (;;) {
    int status = 0;
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done < 0 && errno != EINTR) throw std::runtime_error("waiting for " + name + ": " + std::strerror(errno));
    if (done == pid) {
      ProcessResult r = result_of(status);
      r.timed_out = termed;
      return r;
    }
    const auto now = clock::now();
    if (!termed && now >= term_at) kill(pid, SIGTERM), termed = true;
    if (!killed && now >= kill_at) kill(pid, SIGKILL), killed = true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace

std::string ProcessResult::describe() const {
  if (!signal) return "exit code " + std::to_string(exit_code);
  const char* abbrev = sigabbrev_np(signal);
  return "killed by signal " + std::to_string(signal) + " (" + (abbrev ? "SIG" + std::string(abbrev) + ", " : "") +
         strsignal(signal) + ")";
}

ProcessResult run_process(const std::vector<std::string>& argv, const ProcessOptions& options) {
  SpawnActions actions;
  if (options.quiet) {
    posix_spawn_file_actions_addopen(&actions.actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions.actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  } else if (!options.output_file.empty()) {
    posix_spawn_file_actions_addopen(&actions.actions, STDOUT_FILENO, options.output_file.c_str(),
                                     O_WRONLY | O_CREAT | O_APPEND, 0644);
    posix_spawn_file_actions_adddup2(&actions.actions, STDOUT_FILENO, STDERR_FILENO);
  }
  const pid_t pid = spawn(argv, actions);
  return options.timeout_s > 0 ? wait_for(pid, argv.at(0), options.timeout_s) : wait_for(pid, argv.at(0));
}

ChannelProcess::ChannelProcess(const std::vector<std::string>& argv, int channel_fd) : name_(argv.at(0)) {
  int ends[2];
  if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, ends) != 0)
    throw std::runtime_error(std::string("cannot make a channel: ") + std::strerror(errno));
  // The child's end above the channel's number: dup2 onto itself would keep close-on-exec set.
  const int child_end = fcntl(ends[1], F_DUPFD_CLOEXEC, channel_fd + 1);
  close(ends[1]);
  fd_ = ends[0];
  if (child_end < 0) {
    close(fd_);
    throw std::runtime_error(std::string("cannot place a channel: ") + std::strerror(errno));
  }
  SpawnActions actions;
  posix_spawn_file_actions_adddup2(&actions.actions, child_end, channel_fd);
  try {
    pid_ = spawn(argv, actions);
  } catch (...) {
    close(child_end);
    close(fd_);
    throw;
  }
  close(child_end);  // the child holds the only other end: its death closes the channel
}

ChannelProcess::~ChannelProcess() {
  if (fd_ >= 0) close(fd_);
  if (pid_ > 0) {
    kill(pid_, SIGKILL);
    int status = 0;
    while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
  }
}

bool ChannelProcess::send_line(const std::string& line) {
  const std::string data = line + "\n";
  for (size_t done = 0; done < data.size();) {
    // MSG_NOSIGNAL: a child that died is an answer (false), not a SIGPIPE that ends this process.
    const ssize_t n = send(fd_, data.data() + done, data.size() - done, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return false;
    done += size_t(n);
  }
  return true;
}

std::optional<std::string> ChannelProcess::read_line() {
  std::array<char, 65536> buf;
  for (size_t nl; (nl = pending_.find('\n')) == std::string::npos;) {
    const ssize_t n = read(fd_, buf.data(), buf.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return std::nullopt;
    pending_.append(buf.data(), size_t(n));
  }
  const size_t nl = pending_.find('\n');
  std::string line = pending_.substr(0, nl);
  pending_.erase(0, nl + 1);
  return line;
}

ProcessResult ChannelProcess::wait() {
  close(fd_);
  fd_ = -1;
  const ProcessResult r = wait_for(pid_, name_);
  pid_ = -1;
  return r;
}

std::string self_executable() { return std::filesystem::read_symlink("/proc/self/exe").string(); }

}  // namespace sdb
