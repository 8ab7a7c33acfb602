// The journal of a `run` (DIR/journal.jsonl): a header line saying what the run was asked and on
// which machine and commit, then one line per finished row in the results.json row format, each
// written and fsync'ed as its row completes. A crash, a kill or a full disk loses at most the row
// in flight; `run --resume DIR` reads the journal and measures only the rows it lacks.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "harness/run/plan.h"
#include "harness/results/line_file.h"
#include "harness/results/results.h"

namespace sdb {

inline constexpr int kJournalVersion = 1;
inline constexpr const char* kJournalFile = "journal.jsonl";

// A file the run read (a mesh given by path or found in the corpus) and the hash of its content
// when the run was planned: a resume refuses a file that changed, whose rows would not compare.
struct JournalInput {
  std::string path;
  std::string hash;  // content_hash.h's fnv1a_64 of the bytes, hex
  bool operator==(const JournalInput&) const = default;
};

struct JournalHeader {
  MachineInfo machine;  // with the calibration probes the rows' bandwidth fractions use
  std::string created;  // ISO 8601, UTC
  std::string cwd;      // mesh paths in the selection are relative to it
  RunSelection selection;
  std::vector<std::string> runs;  // the plan's run names, in order
  std::vector<JournalInput> inputs;  // absent in journals written before it: nothing to compare
};

struct JournalContents {
  JournalHeader header;
  std::vector<RunRow> rows;     // in the order they finished
  std::vector<int> row_lines;   // the line each row is on (1 is the header)
  uintmax_t intact_bytes = 0;   // the file up to the end of its last complete line
  bool dropped_torn_line = false;
};

// The first field in which two selections differ ("reps: journalled 5, now 3"); "" when none does.
std::string selection_difference(const RunSelection& journalled, const RunSelection& now);

// Reads a journal. A last line without its newline (a kill or a full disk mid-write) is dropped;
// anything else that does not read as a header or a row is an InputError naming the file and line.
JournalContents read_journal(const std::string& path);

// Appends rows to a journal (a line file, line_file.h). Move-only.
class JournalWriter {
 public:
  // A new journal holding only `header`, written beside `path` and renamed over any earlier one.
  static JournalWriter create(const std::string& path, const JournalHeader& header);
  // The journal read_journal read, cut back to its intact bytes (a torn last line) first.
  static JournalWriter reopen(const std::string& path, uintmax_t intact_bytes);
  // One line, written whole and fsync'ed before it returns. InputError naming the file when the
  // disk refuses it; the journal is then cut back to its last complete row.
  void append(const RunRow& row);

 private:
  explicit JournalWriter(LineFileWriter file) : file_(std::move(file)) {}
  LineFileWriter file_;
};

}  // namespace sdb
