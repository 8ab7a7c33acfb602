#include "harness/results/line_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/core/errors.h"

namespace sdb {
namespace {

std::string read_whole(const std::string& path, const std::string& missing) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path, missing);
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, "not a regular file");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw InputError(path, "cannot read it");
  return text.str();
}

// Writes all of `data` or says why not.
std::string write_all(int fd, const std::string& data) {
  for (size_t done = 0; done < data.size();) {
    const ssize_t n = write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return std::strerror(errno);
    done += size_t(n);
  }
  return fsync(fd) == 0 ? "" : std::strerror(errno);
}

void sync_folder_of(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  const int dir = open(parent.empty() ? "." : parent.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir < 0) return;
  fsync(dir);  // the rename itself survives a power cut
  close(dir);
}

}  // namespace

LineFileContents read_line_file(const std::string& path, const std::string& missing) {
  const std::string text = read_whole(path, missing);
  LineFileContents c;
  for (size_t start = 0;;) {
    const size_t nl = text.find('\n', start);
    if (nl == std::string::npos) {
      // What follows the last newline was cut off mid-write: its line was never written whole.
      c.dropped_torn_line = start < text.size();
      return c;
    }
    c.lines.push_back(text.substr(start, nl - start));
    start = nl + 1;
    c.intact_bytes = start;
  }
}

LineFileWriter::LineFileWriter(std::string path, int fd) : path_(std::move(path)), fd_(fd) {}
LineFileWriter::LineFileWriter(LineFileWriter&& other) noexcept : path_(std::move(other.path_)), fd_(other.fd_) {
  other.fd_ = -1;
}
LineFileWriter::~LineFileWriter() {
  if (fd_ >= 0) close(fd_);
}

LineFileWriter LineFileWriter::create(const std::string& path, const std::string& first_line, const std::string& what) {
  const std::string tmp = path + ".partial";
  const int fd = open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw InputError(path, "cannot start " + what + ": " + std::strerror(errno));
  const std::string failed = write_all(fd, first_line + "\n");
  close(fd);
  std::error_code ec;
  if (!failed.empty()) {
    std::filesystem::remove(tmp, ec);
    throw InputError(path, "cannot start " + what + ": " + failed);
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw InputError(path, "cannot start " + what + " (is it a folder?)");
  }
  sync_folder_of(path);
  return reopen(path, std::filesystem::file_size(path), what);
}

LineFileWriter LineFileWriter::reopen(const std::string& path, uintmax_t intact_bytes, const std::string& what) {
  const int fd = open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd < 0) throw InputError(path, "cannot open " + what + ": " + std::strerror(errno));
  if (ftruncate(fd, off_t(intact_bytes)) != 0) {
    const std::string why = std::strerror(errno);
    close(fd);
    throw InputError(path, "cannot drop the torn last line of " + what + ": " + why);
  }
  return LineFileWriter(path, fd);
}

void LineFileWriter::append(const std::string& line, const std::string& doing) {
  struct stat before {};
  fstat(fd_, &before);
  const std::string failed = write_all(fd_, line + "\n");
  if (failed.empty()) return;
  // A line cut short (a full disk) would read as torn and be dropped; cut it now, so that the
  // file stays whole whatever happens next.
  if (ftruncate(fd_, before.st_size) == 0) fsync(fd_);
  throw InputError(path_, "cannot " + doing + ": " + failed);
}

}  // namespace sdb
