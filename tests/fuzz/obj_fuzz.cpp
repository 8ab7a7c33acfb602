// OBJ reader (harness/mesh/obj_reader.cpp): any bytes give a valid mesh or one InputError line.
#include "harness/mesh/mesh_io.h"
#include "tests/fuzz/contract.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = "fuzz.obj";
  sdb::fuzz::holds_contract(path, [&] { sdb::fuzz::require_valid_mesh(sdb::parse_obj(sdb::fuzz::as_text(data, size), path)); });
  return 0;
}
