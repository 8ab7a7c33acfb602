// A file of whole lines, each written and fsync'ed before the next (a journal): a crash, a kill or
// a full disk loses at most the line in flight, and a reader drops a last line cut off mid-write.
// `run`'s journal (journal.h) and `gpu-check`'s (gpu_check.h) are such files.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace sdb {

struct LineFileContents {
  std::vector<std::string> lines;  // every complete line, without its newline; line i is number i + 1
  uintmax_t intact_bytes = 0;      // the file up to the end of its last complete line
  bool dropped_torn_line = false;  // bytes after the last newline were dropped
};

// InputError naming `path`: `missing` when there is no file, or it is not a regular file or unreadable.
LineFileContents read_line_file(const std::string& path, const std::string& missing);

// Appends lines. Move-only; the file is closed on destruction.
class LineFileWriter {
 public:
  // A new file holding only `first_line`, written beside `path` and renamed over any earlier one,
  // so that the file always begins whole. `what` names the file in errors ("the journal").
  static LineFileWriter create(const std::string& path, const std::string& first_line, const std::string& what);
  // An existing file, cut back to `intact_bytes` (a torn last line) first.
  static LineFileWriter reopen(const std::string& path, uintmax_t intact_bytes, const std::string& what);
  // One line (no newline inside), written whole and fsync'ed before it returns. InputError naming
  // the file when the disk refuses it ("cannot " + `doing` + ": why"); the file is then cut back
  // to its last complete line.
  void append(const std::string& line, const std::string& doing);

  LineFileWriter(LineFileWriter&& other) noexcept;
  LineFileWriter& operator=(LineFileWriter&&) = delete;
  ~LineFileWriter();

 private:
  LineFileWriter(std::string path, int fd);
  std::string path_;
  int fd_ = -1;
};

}  // namespace sdb
