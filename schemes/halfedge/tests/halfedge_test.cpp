// The halfedge rules against OpenSubdiv, on every corpus shape of a rule (the exact schemes' sweep,
// harness/conformance/sweep_corpus.h) at depths 1..5 while the output stays under 400,000
// triangles (depth 1 always):
//   - before projection every refined point equals Far's uniform refinement of the same mesh at
//     its ptex grid point (1e-6 of the diagonal), and every Far vertex is stood for;
//   - after it every vertex equals PrimvarRefiner::Limit's position (1e-6) and its normal is
//     within 0.05 degrees of Far's, where Far's tangents have a direction;
//   - the output has exactly the input's boundary open (scaled by 2^depth), and no ray crack on a
//     closed input (100,000 rays, half aimed at face borders);
//   - cpu-mt's output is cpu's, bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "datasets/generators.h"
#include "harness/conformance/far_oracle.h"
#include "harness/conformance/sweep_corpus.h"
#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/mesh/facts.h"
#include "harness/mesh/osd_topology.h"
#include "harness/validate/watertight.h"
#include "schemes/halfedge/halfedge.h"

using namespace sdb;

namespace {

using conformance::boundary_edges;
using conformance::compare;
using conformance::far_level;
using conformance::Match;
using conformance::sweep_shapes;

const char* scheme_name(SubdivisionRule rule) { return rule == SubdivisionRule::Loop ? "halfedge-loop" : "halfedge-cc"; }

Tessellation run(const ControlMesh& accepted, SubdivisionRule rule, int depth, bool limit, Backend backend = Backend::Cpu) {
  const SchemeInfo& info = find_scheme(scheme_name(rule))->info();
  auto e = halfedge::make_evaluation(accepted, rule, default_request(info, backend, depth), limit);
  e->execute();
  return e->result();
}

struct Totals {
  int shapes = 0, refused = 0, runs = 0;
  double refined = 0, limit = 0, normal = 0;
  long rays = 0, cracks = 0;
};

void sweep(SubdivisionRule rule) {
  const std::vector<std::string> shapes = sweep_shapes(rule);
  if (shapes.empty()) GTEST_SKIP() << "no shared corpus";
  Totals all;
  for (const std::string& name : shapes) {
    ControlMesh accepted;
    try {
      accepted = conformance::sweep_mesh(name, rule, scheme_name(rule));
      run(accepted, rule, 1, false);
    } catch (const InputError& e) {
      std::printf("  refused %s: %s\n", name.c_str(), e.what());
      ++all.refused;
      continue;
    }
    ++all.shapes;
    const double d = bounds_of(accepted.positions).diagonal();
    const bool closed = compute_facts(accepted).closed;
    Totals shape;
    int depth = 1;
    for (; depth <= 5; ++depth) {
      const long faces = num_faces(accepted);
      if (depth > 1 && faces * (rule == SubdivisionRule::Loop ? 1L : 2L) << (2 * depth) > 400000) break;
      const Tessellation t = run(accepted, rule, depth, false);
      const Match m = compare(t, far_level(accepted, rule, depth, false), depth, d, false);
      EXPECT_LE(m.max_rel, 1e-6) << name << " depth " << depth;
      EXPECT_EQ(m.uncovered, 0) << name << " depth " << depth;
      EXPECT_EQ(m.unmatched, 0) << name << " depth " << depth;
      const Tessellation lt = run(accepted, rule, depth, true);
      const conformance::FarLevel far_limit = far_level(accepted, rule, depth, true);
      Match l = compare(lt, far_limit, depth, d, false);
      EXPECT_LE(l.max_rel, 1e-6) << name << " depth " << depth << " (limit)";
      // Normals where Far's tangents are those of the limit and have a side (far_oracle.h).
      conformance::FarLevel sided = far_limit;
      conformance::mark_sideless_normals(accepted, rule, depth, sided);
      l.max_deg = compare(lt, sided, depth, d, true).max_deg;
      // 0.05: 0.017 and 0.026 degrees at depth 5 (catmark_gregory_test5, catmark_single_crease),
      // the same for edgefriend-cc: the shared projection's float masks against the oracle's double.
      EXPECT_LE(l.max_deg, 0.05) << name << " depth " << depth << " (normals)";
      EXPECT_EQ(count_open_edges(lt), boundary_edges(accepted) << depth) << name << " depth " << depth;
      if (closed) {
        const RayCrackReport cracks = ray_crack_check(lt, {50000, 50000, 1});
        EXPECT_EQ(cracks.cracks, 0) << name << " depth " << depth;
        shape.rays += cracks.rays, shape.cracks += cracks.cracks;
      }
      const Tessellation mt = run(accepted, rule, depth, true, Backend::CpuMt);
      EXPECT_TRUE(mt.positions == lt.positions && mt.normals == lt.normals) << name << " depth " << depth << ": cpu-mt";
      shape.refined = std::max(shape.refined, m.max_rel), shape.limit = std::max(shape.limit, l.max_rel);
      shape.normal = std::max(shape.normal, l.max_deg);
      ++all.runs;
    }
    std::printf("  %-44s depths 1..%d  refined %.2g  limit %.2g  normal %.2g deg  %ld rays, %ld cracks\n", name.c_str(),
                depth - 1, shape.refined, shape.limit, shape.normal, shape.rays, shape.cracks);
    all.refined = std::max(all.refined, shape.refined), all.limit = std::max(all.limit, shape.limit);
    all.normal = std::max(all.normal, shape.normal), all.rays += shape.rays, all.cracks += shape.cracks;
  }
  std::printf("%s: %d shapes, %d runs, %d refused; worst refined %.2g, limit %.2g of the diagonal, normal %.2g deg; "
              "%ld rays, %ld cracks\n",
              scheme_name(rule), all.shapes, all.runs, all.refused, all.refined, all.limit, all.normal, all.rays, all.cracks);
}

TEST(HalfedgeSweep, CatmullClarkCorpusEqualsFarRefinementAndLimit) { sweep(SubdivisionRule::CatmullClark); }
TEST(HalfedgeSweep, LoopCorpusEqualsFarRefinementAndLimit) { sweep(SubdivisionRule::Loop); }

// The built-ins without the corpus: a cube (valence 3), a creased cube (sharpness 2: the rules'
// crease-to-smooth blend at depth 2), an icosphere (valence 5).
TEST(Halfedge, BuiltinsEqualFarRefinement) {
  struct Case {
    ControlMesh mesh;
    SubdivisionRule rule;
  };
  for (const Case& c : {Case{gen::cube(), SubdivisionRule::CatmullClark}, Case{gen::creased_cube(2.0f), SubdivisionRule::CatmullClark},
                        Case{gen::icosphere(1), SubdivisionRule::Loop}}) {
    const double d = bounds_of(c.mesh.positions).diagonal();
    for (int depth = 1; depth <= 4; ++depth) {
      const Match m = compare(run(c.mesh, c.rule, depth, false), far_level(c.mesh, c.rule, depth, false), depth, d, false);
      EXPECT_LE(m.max_rel, 1e-6) << c.mesh.name << " depth " << depth;
      EXPECT_EQ(m.uncovered, 0) << c.mesh.name << " depth " << depth;
    }
  }
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

// Where a semi-sharp crease outlasts the depth the row says so (Far's masks take the sharpness
// left as infinite: not the limit there); once it has decayed, nothing is said.
TEST(Halfedge, SemiSharpnessLeftAtTheDepthIsNoted) {
  const ControlMesh cube = gen::creased_cube(2.0f);
  const SchemeInfo& info = find_scheme("halfedge-cc")->info();
  for (int depth = 1; depth <= 3; ++depth) {
    auto e = halfedge::make_evaluation(cube, SubdivisionRule::CatmullClark, default_request(info, Backend::Cpu, depth), true);
    const std::vector<std::string> notes = e->notes();
    const std::string note = notes.empty() ? "" : notes.front();
    if (depth < 2) EXPECT_NE(note.find("semi-sharp creases outlast depth 1"), std::string::npos) << note;
    else EXPECT_TRUE(note.empty()) << depth << ": " << note;
  }
}

}  // namespace
