// Mesh names that generators answer (datasets/manifest.cpp: torus-MxN, quadsphere-K, poleN, ...,
// and the geometry-image scheme's gim-sphere-N / gim-ellipsoid-N, linked here by source since the
// fuzz build links no scheme): a valid mesh of at most 4 M faces, nothing, or one InputError line
// naming the name.
#include "datasets/manifest.h"
#include "schemes/geometry-image/analytic.h"
#include "tests/fuzz/contract.h"

namespace {

constexpr size_t kMaxGeneratedFaces = 4'000'000;

void require_generated(const std::optional<sdb::ControlMesh>& mesh) {
  if (!mesh) return;
  sdb::fuzz::require_valid_mesh(*mesh);
  sdb::fuzz::require(mesh->face_sizes.size() <= kMaxGeneratedFaces, "a generated mesh past 4 M faces");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string name(sdb::fuzz::as_text(data, size));
  sdb::fuzz::holds_contract(name, [&] { require_generated(sdb::generated_mesh(name)); });
  sdb::fuzz::holds_contract(name, [&] { require_generated(sdb::gim::analytic_mesh_from_name(name)); });
  return 0;
}
