// The output folder a run or a report owns: a lock, so that two runs never write one folder at
// once, and publishing by merging, so that files of the user's in it (DIR/plots/mine.png) stay.
#pragma once

#include <filesystem>
#include <string>

namespace sdb {

inline constexpr const char* kLockFile = ".subdivbench.lock";

// Holds DIR/.subdivbench.lock (flock, closed on exec: a worker process does not inherit it) for
// as long as it lives; the file names the holder's process. The kernel drops the lock when the
// holder dies, however it dies.
class FolderLock {
 public:
  // InputError naming `dir` and the other run's process when another holds it.
  static FolderLock take(const std::string& dir);
  FolderLock(FolderLock&& other) noexcept;
  FolderLock& operator=(FolderLock&&) = delete;
  ~FolderLock();

 private:
  explicit FolderLock(int fd) : fd_(fd) {}
  int fd_ = -1;
};

// What a publish put into a folder (one name a line), so that the next publish removes its own
// stale files and nothing else.
inline constexpr const char* kPublishedList = ".subdivbench-files";

// Moves every entry of `from` into `to` by rename: a file replaces the file of its name, a folder
// is merged the same way into the folder of its name. Of what `to` holds besides, the files the
// previous merge listed in `to`'s kPublishedList go (an earlier set's plot of a mesh no longer
// run); the rest (a file of the user's) stays. Throws InputError naming the entry that cannot be
// moved. `prune` false (the output folder itself: results.json and the report, whose files a
// `--no-report` run leaves as they were) neither removes nor lists; its subfolders always do.
void merge_into_folder(const std::filesystem::path& from, const std::filesystem::path& to, bool prune = true);

}  // namespace sdb
