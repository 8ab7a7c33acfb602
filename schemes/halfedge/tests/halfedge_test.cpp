// The halfedge rules against OpenSubdiv and the yardstick, on every corpus shape of each rule
// (harness/conformance/refined_sweep.h: Far's refinement vertex for vertex, Far's limit positions,
// every normal against the limit on its face's side, watertight, cpu-mt bit for bit).
#include <gtest/gtest.h>

#include "datasets/generators.h"
#include "harness/conformance/refined_sweep.h"
#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "schemes/halfedge/halfedge.h"

using namespace sdb;

namespace {

const char* scheme_name(SubdivisionRule rule) { return rule == SubdivisionRule::Loop ? "halfedge-loop" : "halfedge-cc"; }

conformance::RefinedPeer peer(SubdivisionRule rule) {
  return {scheme_name(rule), rule, [rule](const ControlMesh& accepted, int depth, bool limit, Backend backend) {
            const SchemeInfo& info = find_scheme(scheme_name(rule))->info();
            auto e = halfedge::make_evaluation(accepted, rule, default_request(info, backend, depth), limit);
            e->execute();
            return e->result();
          }};
}

TEST(HalfedgeSweep, CatmullClarkCorpusEqualsFarRefinementAndLimit) {
  conformance::sweep_refined_peer(peer(SubdivisionRule::CatmullClark));
}
TEST(HalfedgeSweep, LoopCorpusEqualsFarRefinementAndLimit) { conformance::sweep_refined_peer(peer(SubdivisionRule::Loop)); }

// The built-ins without the corpus: a cube (valence 3), a creased cube (sharpness 2: the rules'
// crease-to-smooth blend at depth 2), an icosphere (valence 5).
TEST(Halfedge, BuiltinsEqualFarRefinement) {
  conformance::expect_refined_equals_far(peer(SubdivisionRule::CatmullClark), gen::cube());
  conformance::expect_refined_equals_far(peer(SubdivisionRule::CatmullClark), gen::creased_cube(2.0f));
  conformance::expect_refined_equals_far(peer(SubdivisionRule::Loop), gen::icosphere(1));
}

}  // namespace

namespace {

// A level past 32-bit indices is refused before anything is made (an Unsupported row, exit 2 at
// `validate`), not allocated: 81,920 triangles at depth 8 would be 1.6e10 halfedges.
TEST(Halfedge, DepthsPastIndicesAreRefusedUpFront) {
  const ControlMesh big = gen::icosphere(6);
  for (SubdivisionRule rule : {SubdivisionRule::Loop, SubdivisionRule::CatmullClark}) {
    const SchemeInfo& info = find_scheme(scheme_name(rule))->info();
    EXPECT_THROW(halfedge::make_evaluation(big, rule, default_request(info, Backend::Cpu, 8), true), Unsupported);
  }
}

// Where a semi-sharp crease outlasts the depth (sharpness 2 at depth 1), the projection is the
// limit all the same: the ring refined on past the sharpness (harness/refined/exact_masks.h; Far's
// masks, which take what is left as infinite, were 63 degrees off on catmark_chaikin0), and no
// row says otherwise.
TEST(Halfedge, SemiSharpnessLeftAtTheDepthIsProjectedToTheLimit) {
  const ControlMesh cube = gen::creased_cube(2.0f);
  const SchemeInfo& info = find_scheme("halfedge-cc")->info();
  for (int depth = 1; depth <= 3; ++depth) {
    conformance::expect_limit_is_exact(peer(SubdivisionRule::CatmullClark), cube, depth);
    EXPECT_TRUE(find_scheme(info.name)->prepare(cube, default_request(info, Backend::Cpu, depth))->notes().empty());
  }
}

}  // namespace
