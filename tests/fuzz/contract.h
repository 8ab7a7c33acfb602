// The contract every fuzz target holds the code under test to: it returns a valid structure or
// throws InputError with one line that starts with where the input came from. Any other
// exception, a broken structure, a crash, a sanitizer report or a hang is a finding: the target
// aborts (or libFuzzer reports it), and the input is kept as a regression input.
#pragma once

#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>
#include <string_view>
#include <typeinfo>

#include "harness/core/control_mesh.h"
#include "harness/core/errors.h"

namespace sdb::fuzz {

[[noreturn]] void finding(const std::string& what);

inline void require(bool ok, const char* what) {
  if (!ok) finding(what);
}

void require_one_line_naming(const std::string& message, const std::string& where);

// Runs `body`; an InputError must name `where` first and be one line.
template <class Body>
void holds_contract(const std::string& where, Body&& body) {
  try {
    body();
  } catch (const InputError& e) {
    require_one_line_naming(e.what(), where);
  } catch (const std::exception& e) {
    finding(std::string("not an InputError: ") + typeid(e).name() + ": " + e.what());
  } catch (...) {
    finding("an exception that is not a std::exception");
  }
}

// Counts consistent, every index (faces, creases, corners, holes) in range, faces of 3 or more
// vertices, finite coordinates and sharpness: checked here independently of check_mesh_data.
void require_valid_mesh(const ControlMesh& mesh);

// A path of this process's own in the temporary folder, ending in `suffix`, removed at exit.
std::string scratch_path(const std::string& suffix);

// A file holding `data` for the readers that take a path (OpenMesh, results, gate configuration):
// scratch_path(extension), rewritten for every input.
std::string write_input_file(std::string_view data, const std::string& extension);

inline std::string_view as_text(const uint8_t* data, size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

}  // namespace sdb::fuzz
