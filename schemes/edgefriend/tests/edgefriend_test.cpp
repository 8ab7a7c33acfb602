// Edge-Friend against OpenSubdiv and the yardstick, on every Catmull-Clark corpus shape
// (harness/conformance/refined_sweep.h: Far's refinement vertex for vertex, Far's limit positions,
// every normal against the limit on its face's side, watertight, cpu-mt bit for bit).
#include <gtest/gtest.h>

#include "datasets/generators.h"
#include "harness/conformance/refined_sweep.h"
#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "schemes/edgefriend/edgefriend.h"

using namespace sdb;

namespace {

constexpr SubdivisionRule kCC = SubdivisionRule::CatmullClark;

Tessellation run(const ControlMesh& accepted, int depth, bool limit, Backend backend = Backend::Cpu) {
  const SchemeInfo& info = find_scheme("edgefriend-cc")->info();
  auto e = edgefriend::make_evaluation(accepted, default_request(info, backend, depth), limit);
  e->execute();
  return e->result();
}

const conformance::RefinedPeer kPeer{"edgefriend-cc", kCC, [](const ControlMesh& m, int depth, bool limit, Backend b) {
                                       return run(m, depth, limit, b);
                                     }};

TEST(EdgeFriendSweep, CorpusEqualsFarRefinementAndLimit) { conformance::sweep_refined_peer(kPeer); }

// The built-ins without the corpus: a cube (valence 3), a creased cube (sharpness 2: the crease-to-
// smooth blend at depth 3), a torus (genus 1: V = Q), a quad sphere.
TEST(EdgeFriend, BuiltinsEqualFarRefinement) {
  for (const ControlMesh& mesh : {gen::cube(), gen::creased_cube(2.0f), gen::torus(8, 6), gen::quad_sphere(3)})
    conformance::expect_refined_equals_far(kPeer, mesh);
}

// A level past 32-bit indices is refused before anything is made (an Unsupported row, exit 2 at
// `validate`), not allocated.
TEST(EdgeFriend, DepthsPastIndicesAreRefusedUpFront) {
  const ControlMesh big = gen::quad_sphere(64);
  const SchemeInfo& info = find_scheme("edgefriend-cc")->info();
  EXPECT_THROW(edgefriend::make_evaluation(big, default_request(info, Backend::Cpu, 8), true), Unsupported);
}

// Chaikin creasing with semi-sharp creases is not the paper's uniform decay: refused, naming it.
TEST(EdgeFriend, ChaikinSemiSharpCreasesAreRefused) {
  ControlMesh cube = gen::creased_cube(2.5f);
  cube.crease_method = CreaseMethod::Chaikin;
  try {
    run(cube, 2, true);
    FAIL() << "accepted Chaikin creasing";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Chaikin"), std::string::npos) << e.what();
  }
  cube = gen::creased_cube(10.0f);  // infinitely sharp: both rules agree
  cube.crease_method = CreaseMethod::Chaikin;
  EXPECT_NO_THROW(run(cube, 2, true));
}

// Where a semi-sharp crease outlasts the depth (sharpness 2 at depth 1), the projection is the
// limit all the same: the ring refined on past the sharpness (harness/refined/exact_masks.h; Far's
// masks, which take what is left as infinite, were 63 degrees off on catmark_chaikin0), and no
// row says otherwise.
TEST(EdgeFriend, SemiSharpnessLeftAtTheDepthIsProjectedToTheLimit) {
  const ControlMesh cube = gen::creased_cube(2.0f);
  const SchemeInfo& info = find_scheme("edgefriend-cc")->info();
  for (int depth = 1; depth <= 3; ++depth) {
    conformance::expect_limit_is_exact(kPeer, cube, depth);
    EXPECT_TRUE(find_scheme(info.name)->prepare(cube, default_request(info, Backend::Cpu, depth))->notes().empty());
  }
}

}  // namespace
