#include "harness/bench/progress.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ostream>

namespace sdb {

namespace {

bool is_terminal(int fd) {
  if (!::isatty(fd)) return false;
  const char* term = std::getenv("TERM");
  return !(term && std::strcmp(term, "dumb") == 0);
}

}  // namespace

bool stdout_is_terminal() { return is_terminal(STDOUT_FILENO); }
bool stderr_is_terminal() { return is_terminal(STDERR_FILENO); }

int terminal_columns() {
  winsize w{};
  if (::ioctl(STDOUT_FILENO, TIOCGWINSZ, &w) == 0 && w.ws_col > 0) return w.ws_col;
  return 80;
}

std::string format_duration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buf[32];
  if (s < 60) std::snprintf(buf, sizeof buf, "%lds", s);
  else if (s < 3600) std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
  else std::snprintf(buf, sizeof buf, "%ldh%02ldm", s / 3600, (s % 3600) / 60);
  return buf;
}

double Progress::steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

Progress::Progress(std::ostream& out, bool terminal, size_t total, Clock clock, int columns)
    : out_(out), terminal_(terminal), total_(total), clock_(std::move(clock)), columns_(std::max(columns, 20)),
      start_(clock_()) {}

Progress::~Progress() { close(); }

double Progress::elapsed() const { return clock_() - start_; }

double Progress::eta() const {
  if (done_ == 0 || total_ == 0) return -1;
  return elapsed() / double(done_) * double(total_ > done_ ? total_ - done_ : 0);
}

std::string Progress::counter() const {
  if (total_ == 0) return "[" + std::to_string(done_) + "] " + format_duration(elapsed()) + " elapsed";
  const int width = static_cast<int>(std::to_string(total_).size());
  char count[64];
  std::snprintf(count, sizeof count, "[%*zu/%zu]", width, done_, total_);
  // Durations padded to one width: the rows after the counter stay in columns.
  char times[64];
  const double left = eta();
  std::snprintf(times, sizeof times, " %5s elapsed, ETA %5s", format_duration(elapsed()).c_str(),
                left < 0 ? "--" : format_duration(left).c_str());
  return std::string(count) + times;
}

void Progress::begin(const std::string& item) {
  current_ = item;
  if (terminal_) draw_status();
}

void Progress::done(const std::string& head, const std::string& tail, bool keep) {
  ++done_;
  current_.clear();
  if (!terminal_) {
    out_ << head << " " << counter() << tail << "\n" << std::flush;
    return;
  }
  if (keep) {
    clear_status();
    out_ << head << tail << "\n";
  }
  draw_status();
}

void Progress::note(const std::string& line) {
  clear_status();
  out_ << line << "\n" << std::flush;
  if (terminal_ && !current_.empty()) draw_status();
}

void Progress::close() {
  clear_status();
  out_ << std::flush;
}

void Progress::draw_status() {
  std::string status = counter();
  if (!current_.empty()) status += ": " + current_;
  if (status.size() >= size_t(columns_)) status = status.substr(0, size_t(columns_) - 4) + "...";
  out_ << "\r\033[K" << status << std::flush;
  status_shown_ = true;
}

void Progress::clear_status() {
  if (!status_shown_) return;
  out_ << "\r\033[K";
  status_shown_ = false;
}

}  // namespace sdb
