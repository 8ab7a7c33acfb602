// What the text readers (OBJ, OFF, PLY) share: lines with their numbers, blank-separated tokens,
// and checked conversions that throw InputError("path:line", reason) quoting at most 40
// characters of the offending token.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "harness/core/errors.h"

namespace sdb::text {

inline std::string quoted(std::string_view tok) {
  constexpr size_t kMax = 40;
  return "'" + std::string(tok.substr(0, kMax)) + (tok.size() > kMax ? "...'" : "'");
}

// Blanks as C's isspace has them, less the line breaks: a form feed or vertical tab after `v`
// separates like a space (a reader that split on spaces and tabs alone dropped such lines).
inline bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

inline std::string_view trim(std::string_view s) {
  while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_blank(s.back())) s.remove_suffix(1);
  return s;
}

inline std::vector<std::string_view> tokens(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_blank(line[i])) ++i;
    size_t j = i;
    while (j < line.size() && !is_blank(line[j])) ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

// A UTF-8 byte-order mark is not part of the first line.
inline size_t after_bom(std::string_view text) { return text.substr(0, 3) == "\xEF\xBB\xBF" ? 3 : 0; }

struct Line {
  int number;
  std::string_view text;  // trimmed
};

// The line starting at `pos` (untrimmed, without its break) and where the next one starts: a line
// ends at LF, CR or CRLF alike (a file with CR-only endings read as one long line).
inline std::pair<std::string_view, size_t> next_line(std::string_view text, size_t pos) {
  size_t end = text.find_first_of("\r\n", pos);
  if (end == std::string_view::npos) return {text.substr(pos), text.size()};
  const size_t next = end + 1 < text.size() && text[end] == '\r' && text[end + 1] == '\n' ? end + 2 : end + 1;
  return {text.substr(pos, end - pos), next};
}

// Every line of `text` from `pos` on, numbered from `first_number`; blank lines kept (empty text).
inline std::vector<Line> split_lines(std::string_view text, size_t pos = 0, int first_number = 1) {
  std::vector<Line> out;
  int no = first_number;
  while (pos < text.size()) {
    const auto [line, next] = next_line(text, pos);
    out.push_back({no++, trim(line)});
    pos = next;
  }
  return out;
}

class LineParser {
 public:
  LineParser(const std::string& path, int line) : where_(at_line(path, line)) {}

  [[noreturn]] void fail(const std::string& reason) const { throw InputError(where_, reason); }

  // A coordinate too small for a float (-1e-50, a denormal) is a number: it reads as the nearest
  // float (zero or a denormal, with its sign); only one too large for a float is out of range.
  float number(std::string_view tok) const {
    std::string_view t = tok;
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);
    float value = 0;
    auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (ec == std::errc::result_out_of_range && ptr == t.data() + t.size()) {
      if (const std::optional<float> tiny = underflowing(t)) return *tiny;
      fail("number out of range " + quoted(tok));
    }
    if (ec != std::errc() || ptr != t.data() + t.size() || t.empty()) fail("malformed number " + quoted(tok));
    return value;
  }
  long integer(std::string_view tok) const { return convert<long>(tok, "integer"); }

  // A 0-based index below `count` (vertices or faces): never wrapped into another element.
  int index(std::string_view tok, long count, const char* what) const {
    const long v = integer(tok);
    if (v < 0 || v >= count)
      fail(std::string(what) + " index " + std::string(tok.substr(0, 40)) + " out of range (mesh has " +
           std::to_string(count) + " " + (std::string(what) == "vertex" ? "vertices" : std::string(what) + "s") + ")");
    return static_cast<int>(v);
  }

 private:
  // The whole token, an optional leading '+', nothing else; `kind` names it in the message.
  template <class T>
  T convert(std::string_view tok, const char* kind) const {
    std::string_view t = tok;
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);
    T value{};
    auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (ec == std::errc::result_out_of_range) fail(std::string(kind) + " out of range " + quoted(tok));
    if (ec != std::errc() || ptr != t.data() + t.size() || t.empty()) fail("malformed " + std::string(kind) + " " + quoted(tok));
    return value;
  }

  // The float nearest a decimal number that from_chars found out of range, when it is below the
  // smallest normal float in magnitude; nullopt when it is too large. The digits decide: a
  // mantissa of digits with a decimal exponent (the only form from_chars read).
  static std::optional<float> underflowing(std::string_view t) {
    const std::string digits(t);
    const long double v = std::strtold(digits.c_str(), nullptr);
    if (std::fabs(v) >= std::numeric_limits<float>::min()) return std::nullopt;
    const float f = static_cast<float>(v);
    return f == 0 ? 0.0f : f;  // no negative zero: one zero, whatever the sign of what underflowed
  }

  std::string where_;
};

}  // namespace sdb::text
