// OFF (off_reader.cpp, off_binary.cpp), ASCII or binary as read_mesh dispatches.
#include "harness/mesh/mesh_io.h"
#include "tests/fuzz/contract.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text = sdb::fuzz::as_text(data, size);
  const std::string path = "fuzz.off";
  sdb::fuzz::holds_contract(path, [&] {
    sdb::fuzz::require_valid_mesh(sdb::is_binary_off(text) ? sdb::parse_binary_off(text, path) : sdb::parse_off(text, path));
  });
  return 0;
}
