// Text from data (file names, tokens, tags) made safe to print on a terminal.
#pragma once

#include <string>

namespace sdb {

// `text` safe to print on a terminal: control characters (a newline or an escape sequence in a
// file name, say) and the C1 controls as UTF-8 spell themselves as \n, \t or \xHH, and a
// backslash as \\, so one message stays one line and nothing in data steers the terminal.
inline std::string printable(const std::string& text) {
  static const char* const hex = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    const bool c1 = c == 0xc2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) >= 0x80 &&
                    static_cast<unsigned char>(text[i + 1]) <= 0x9f;
    if (c == '\n') out += "\\n";
    else if (c == '\t') out += "\\t";
    else if (c == '\\') out += "\\\\";
    else if (c < 0x20 || c == 0x7f) out += std::string("\\x") + hex[c >> 4] + hex[c & 15];
    else if (c1) {
      const auto d = static_cast<unsigned char>(text[++i]);
      out += std::string("\\xc2\\x") + hex[d >> 4] + hex[d & 15];
    } else out += text[i];
  }
  return out;
}

}  // namespace sdb
