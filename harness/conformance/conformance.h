// The conformance suite every scheme instantiates with one line in its tests/:
//
//   SDB_CONFORMANCE_SUITE("cpatch-2pass", "cpatch-1pass", "cpatch-tess");
//
// For every named scheme x backend it declares x closed mesh of a small set that it accepts
// (built-ins, plus the shared corpus when present, plus any the scheme's test adds with
// SDB_CONFORMANCE_SUITE_WITH_MESHES) x up to two of its default levels:
//   - the output is well formed: one normal and one SurfaceCoord per vertex, indices in range,
//     every SurfaceCoord inside its face (u, v in [0, 1]; u + v <= 1 on a Loop triangle), or no
//     SurfaceCoords at all for a scheme that declares none (SchemeInfo::surface_coords);
//   - 0 open edges by exact welding and 0 ray cracks (20,000 random and 20,000 border lines);
//   - the deviation from the reference limit at the same SurfaceCoords is within the scheme's
//     declared bound (SchemeInfo::bound);
//   - cpu-mt gives the cpu's output bit for bit; vulkan lies within 1e-5 of the diagonal of it
//     (for schemes with a cpu backend).
// And for every named scheme x mesh of the set it does not accept: accept_mesh() refuses it with
// an InputError (exit code 2 at the command line), never another exception; a level below every
// sensible one (-1) is declined with a reason, not run.
// Vulkan cases run on the tests' shared context with validation on, and skip without a device.
// ctest runs an executable's cases as one test, `<executable>.Conformance`, in one process (the
// reference and the Vulkan pipelines are made once); one case alone: the executable with
// --gtest_filter='Conformance/SchemeConformance.*/<scheme>_<backend>_<mesh>_<level>'.
#pragma once

#include <gtest/gtest.h>

#include <ostream>
#include <string>
#include <vector>

#include "harness/core/backend.h"
#include "harness/core/control_mesh.h"

namespace sdb::conformance {

struct Case {
  std::string scheme;
  Backend backend = Backend::Cpu;
  std::string mesh;
  int level = 0;
};

struct Refusal {
  std::string scheme, mesh;
};

// The closed meshes every scheme is tried on (those present), then `extra`.
std::vector<std::string> conformance_meshes(const std::vector<std::string>& extra = {});

std::vector<Case> cases_for(const std::vector<std::string>& schemes, const std::vector<std::string>& extra_meshes = {});
std::vector<Refusal> refusals_for(const std::vector<std::string>& schemes);

// The largest distance between a[i] and b[i] (b at least as long as a), in double.
double max_distance(const std::vector<Point3>& a, const std::vector<Point3>& b);

// How GoogleTest prints a case (and ctest lists it): scheme/backend/mesh/level.
void PrintTo(const Case& c, std::ostream* out);
void PrintTo(const Refusal& r, std::ostream* out);

std::string case_name(const ::testing::TestParamInfo<Case>& info);
std::string refusal_name(const ::testing::TestParamInfo<Refusal>& info);

class SchemeConformance : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override;
  void TearDown() override;

 private:
  bool vulkan_ = false;
  unsigned long long validation_errors_before_ = 0;
};

class SchemeRefusal : public ::testing::TestWithParam<Refusal> {};

}  // namespace sdb::conformance

// The generators run when GoogleTest registers its tests, after every static registration.
// (GoogleTest pastes the suite's name into identifiers: it has to be a bare name here.)
#define SDB_CONFORMANCE_SUITE_WITH_MESHES(meshes, ...)                                                         \
  using ::sdb::conformance::SchemeConformance;                                                                 \
  using ::sdb::conformance::SchemeRefusal;                                                                     \
  INSTANTIATE_TEST_SUITE_P(Conformance, SchemeConformance,                                                     \
                           ::testing::ValuesIn(::sdb::conformance::cases_for({__VA_ARGS__}, meshes)),          \
                           ::sdb::conformance::case_name);                                                     \
  INSTANTIATE_TEST_SUITE_P(Conformance, SchemeRefusal,                                                         \
                           ::testing::ValuesIn(::sdb::conformance::refusals_for({__VA_ARGS__})),               \
                           ::sdb::conformance::refusal_name)
#define SDB_CONFORMANCE_SUITE(...) SDB_CONFORMANCE_SUITE_WITH_MESHES(std::vector<std::string>{}, __VA_ARGS__)
