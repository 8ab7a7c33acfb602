// For the readers' tests: what a reader says of a file holding given text.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "harness/core/errors.h"

namespace sdb {

// The message of the InputError `read(path)` raises on a file holding `text`, or "" when it reads.
// The file is `name` (its extension picks the format where the reader goes by it) with this
// process's id in front, in the temporary directory, and is removed afterwards.
template <class Reader>
std::string input_error_of_file(const std::string& name, const std::string& text, Reader read) {
  const std::filesystem::path p = std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "_" + name);
  std::ofstream(p, std::ios::binary) << text;
  std::string message;
  try {
    read(p.string());
  } catch (const InputError& e) {
    message = e.what();
  }
  std::filesystem::remove(p);
  return message;
}

}  // namespace sdb
