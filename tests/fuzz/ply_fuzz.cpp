// PLY: checked against its header (ply_check.cpp), then read by OpenMesh (openmesh_reader.cpp),
// through read_mesh as every verb reads a file.
#include "harness/mesh/mesh_io.h"
#include "tests/fuzz/contract.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = sdb::fuzz::write_input_file(sdb::fuzz::as_text(data, size), ".ply");
  sdb::fuzz::holds_contract(path, [&] { sdb::fuzz::require_valid_mesh(sdb::read_mesh(path)); });
  return 0;
}
