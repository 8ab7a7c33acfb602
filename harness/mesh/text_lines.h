// What the text readers (OBJ, OFF, PLY) share: lines with their numbers, blank-separated tokens,
// and checked conversions that throw InputError("path:line", reason) quoting at most 40
// characters of the offending token.
#pragma once

#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "harness/core/errors.h"

namespace sdb::text {

inline std::string quoted(std::string_view tok) {
  constexpr size_t kMax = 40;
  return "'" + std::string(tok.substr(0, kMax)) + (tok.size() > kMax ? "...'" : "'");
}

inline std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

inline std::vector<std::string_view> tokens(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
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

// Every line of `text` from `pos` on, numbered from `first_number`; blank lines kept (empty text).
inline std::vector<Line> split_lines(std::string_view text, size_t pos = 0, int first_number = 1) {
  std::vector<Line> out;
  int no = first_number;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    out.push_back({no++, trim(text.substr(pos, end - pos))});
    pos = end + 1;
  }
  return out;
}

class LineParser {
 public:
  LineParser(const std::string& path, int line) : where_(at_line(path, line)) {}

  [[noreturn]] void fail(const std::string& reason) const { throw InputError(where_, reason); }

  float number(std::string_view tok) const { return convert<float>(tok, "number"); }
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

  std::string where_;
};

}  // namespace sdb::text
