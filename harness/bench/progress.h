// Progress of a long verb (run, bench, paper): rows done of the total, time elapsed, an estimate of
// the time left and the row being measured. On a terminal one status line is rewritten in place
// (rows worth keeping are printed above it); otherwise, as in a CI log or a pipe, one plain line
// per finished row, so that no carriage returns or escape codes land in a file.
#pragma once

#include <cstddef>
#include <functional>
#include <iosfwd>
#include <string>

namespace sdb {

// Whether standard output (error) is a terminal that can rewrite a line (not a pipe, a file or
// TERM=dumb).
bool stdout_is_terminal();
bool stderr_is_terminal();
// Columns of the terminal on standard output (80 when unknown).
int terminal_columns();

// "42s", "3m05s", "1h02m".
std::string format_duration(double seconds);

class Progress {
 public:
  using Clock = std::function<double()>;  // seconds from any fixed origin
  static double steady_seconds();

  // `total` items (0: not known in advance, no estimate); `columns` bounds the status line on a terminal (a wrapped line cannot be
  // rewritten by a carriage return).
  Progress(std::ostream& out, bool terminal, size_t total, Clock clock = steady_seconds, int columns = 80);
  ~Progress();  // clears the status line, as close() does

  // An item starts: on a terminal the status line names it.
  void begin(const std::string& item);
  // The item finished: `head` names it, `tail` is its result. Plain output prints one line, the
  // count between head and tail (a log's lines still start with what they are about); a terminal
  // prints head and tail above the status line only when `keep` (a failure, a crack).
  void done(const std::string& head, const std::string& tail, bool keep);
  // A message that is not a row (a note, a warning): printed whole in either mode.
  void note(const std::string& line);
  // Leaves the terminal without a status line; idempotent.
  void close();

  size_t finished() const { return done_; }
  double elapsed() const;
  // Seconds left at the pace so far; negative before the first item finishes or without a total.
  double eta() const;

 private:
  std::string counter() const;  // "[ 12/738] 1m02s elapsed, ETA 3m10s"
  void draw_status();
  void clear_status();

  std::ostream& out_;
  bool terminal_;
  size_t total_, done_ = 0;
  Clock clock_;
  int columns_;
  double start_;
  std::string current_;
  bool status_shown_ = false;
};

}  // namespace sdb
