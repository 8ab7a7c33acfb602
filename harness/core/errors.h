// The error taxonomy at the seam between the harness and the schemes. Every scheme and every
// harness module throws one of these for anything a user can cause; the CLI maps them:
//   InputError   bad input, bad usage or a mesh a scheme cannot take: one line, exit code 2.
//   Unsupported  a device or size limit a request runs into (an output past the device's memory,
//                a rate past a shader stage's output limit): the run becomes an "unsupported"
//                row carrying the reason; asked for on its own (validate), exit code 2.
// Anything else is an internal error (exit code 3): a bug, not an answer.
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

class Unsupported : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline std::string at_line(const std::string& file, int line) {
  return line > 0 ? file + ":" + std::to_string(line) : file;
}

}  // namespace sdb
