#include "harness/results/output_folder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <set>
#include <string>

#include "harness/core/errors.h"

namespace fs = std::filesystem;

namespace sdb {
namespace {

// The process the lock file names ("1234"), or "unknown" when it names none yet.
std::string holder(int fd) {
  char buf[32] = {};
  const ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
  std::string pid(buf, n > 0 ? size_t(n) : 0);
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  return pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos ? "unknown" : pid;
}

}  // namespace

FolderLock FolderLock::take(const std::string& dir) {
  const fs::path path = fs::path(dir) / kLockFile;
  const int fd = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw InputError(dir, std::string("cannot lock the output folder: ") + std::strerror(errno));
  if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const std::string why = errno == EWOULDBLOCK ? "another run (process " + holder(fd) +
                                                       ") is writing this folder: wait for it, or give this run another --out"
                                                 : std::string("cannot lock the output folder: ") + std::strerror(errno);
    close(fd);
    throw InputError(dir, why);
  }
  const std::string pid = std::to_string(getpid()) + "\n";
  if (ftruncate(fd, 0) != 0 || pwrite(fd, pid.data(), pid.size(), 0) != ssize_t(pid.size())) {
    // The lock holds without the name; only a second run's message loses the process number.
  }
  return FolderLock(fd);
}

FolderLock::FolderLock(FolderLock&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }

FolderLock::~FolderLock() {
  if (fd_ >= 0) close(fd_);  // releases the flock
}

namespace {

// The names a folder's list of published files gives: plain names only (the list is data in the
// user's folder; "../x" or "/etc/x" in it must not make a publish remove anything elsewhere).
std::set<std::string> listed_files(const fs::path& folder) {
  std::set<std::string> names;
  std::ifstream in(folder / kPublishedList);
  for (std::string name; std::getline(in, name);)
    if (!name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos && name != kPublishedList)
      names.insert(name);
  return names;
}

void write_list(const fs::path& folder, const std::set<std::string>& names) {
  const fs::path tmp = folder / (std::string(kPublishedList) + ".partial");
  {
    std::ofstream out(tmp, std::ios::trunc);
    for (const std::string& n : names) out << n << "\n";
    if (!out) return;  // the list only lets the next publish remove this one's files
  }
  std::error_code ec;
  fs::rename(tmp, folder / kPublishedList, ec);
}

}  // namespace

void merge_into_folder(const fs::path& from, const fs::path& to, bool prune) {
  std::error_code ec;
  fs::create_directories(to, ec);
  if (!fs::is_directory(to)) throw InputError(to.string(), "is not a folder: cannot publish into it");
  const std::set<std::string> earlier = prune ? listed_files(to) : std::set<std::string>{};
  std::set<std::string> ours;
  for (const auto& entry : fs::directory_iterator(from)) {
    const std::string name = entry.path().filename().string();
    if (name == kPublishedList) continue;  // a list staged with the files: this folder's is written below
    ours.insert(name);
    const fs::path target = to / name;
    if (entry.is_directory() && !entry.is_symlink() && fs::is_directory(fs::symlink_status(target))) {
      merge_into_folder(entry.path(), target, true);
      continue;
    }
    fs::rename(entry.path(), target, ec);
    if (ec) throw InputError(target.string(), "cannot replace: " + ec.message());
  }
  // A file the earlier set published and this one does not (a plot of a mesh no longer run) goes;
  // anything not listed is not ours and stays.
  for (const std::string& name : earlier)
    if (!ours.count(name) && fs::is_regular_file(fs::symlink_status(to / name, ec))) fs::remove(to / name, ec);
  if (prune) write_list(to, ours);
}

}  // namespace sdb
