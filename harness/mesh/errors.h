// InputError: bad input or a mesh a scheme cannot take. The CLI prints what() as one line and
// exits with code 2; nothing is written as if the run were whole.
#pragma once

#include <stdexcept>
#include <string>

namespace sdb {

class InputError : public std::runtime_error {
 public:
  // where: "path", "path:line", or a mesh name; reason: what is wrong, without a trailing period.
  InputError(const std::string& where, const std::string& reason)
      : std::runtime_error(where.empty() ? reason : where + ": " + reason) {}
};

inline std::string at_line(const std::string& file, int line) {
  return line > 0 ? file + ":" + std::to_string(line) : file;
}

}  // namespace sdb
