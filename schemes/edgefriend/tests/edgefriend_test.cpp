// Edge-Friend against OpenSubdiv, on every Catmull-Clark corpus shape (the exact schemes' sweep,
// harness/conformance/sweep_corpus.h) at depths 1..5 while the output stays under 400,000
// triangles (depth 1 always):
//   - before projection every refined point equals Far's uniform refinement of the same mesh at
//     its ptex grid point (1e-6 of the diagonal), and every Far vertex is stood for;
//   - after it every vertex equals PrimvarRefiner::Limit's position (1e-6) and its normal is
//     within 0.05 degrees of Far's (kNormalDeg), where Far's tangents have a side;
//   - the output has exactly the input's boundary open (scaled by 2^depth), and no ray crack on a
//     closed input (100,000 rays, half aimed at face borders);
//   - cpu-mt's output is cpu's, bit for bit.
#include <gtest/gtest.h>

#include <cstdio>

#include "datasets/generators.h"
#include "harness/conformance/far_oracle.h"
#include "harness/conformance/sweep_corpus.h"
#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/mesh/facts.h"
#include "harness/validate/watertight.h"
#include "schemes/edgefriend/edgefriend.h"

using namespace sdb;

namespace {

using conformance::boundary_edges;
using conformance::compare;
using conformance::far_level;
using conformance::Match;
constexpr SubdivisionRule kCC = SubdivisionRule::CatmullClark;
// Normals: halfedge-cc's sweep and this one meet the same largest angles, 0.017 and 0.026 degrees
// at depth 5 (catmark_gregory_test5, catmark_single_crease): the shared projection's float masks
// (harness/refined) against the oracle's double, not the refinement (positions within 5.1e-7).
constexpr double kNormalDeg = 0.05;

Tessellation run(const ControlMesh& accepted, int depth, bool limit, Backend backend = Backend::Cpu) {
  const SchemeInfo& info = find_scheme("edgefriend-cc")->info();
  auto e = edgefriend::make_evaluation(accepted, default_request(info, backend, depth), limit);
  e->execute();
  return e->result();
}

struct Totals {
  int shapes = 0, refused = 0, runs = 0;
  long points = 0, sideless = 0;  // refined points compared; normals left out (far_oracle.h)
  double refined = 0, limit = 0, normal = 0;
  long rays = 0, cracks = 0;
};

TEST(EdgeFriendSweep, CorpusEqualsFarRefinementAndLimit) {
  const std::vector<std::string> shapes = conformance::sweep_shapes(kCC);
  if (shapes.empty()) GTEST_SKIP() << "no shared corpus";
  Totals all;
  for (const std::string& name : shapes) {
    ControlMesh accepted;
    try {
      accepted = conformance::sweep_mesh(name, kCC, "edgefriend-cc");
      run(accepted, 1, false);
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
      if (depth > 1 && long(accepted.face_vertices.size()) * 2L << (2 * depth - 2) > 400000) break;
      const Tessellation t = run(accepted, depth, false);
      const Match m = compare(t, far_level(accepted, kCC, depth, false), depth, d, false);
      EXPECT_LE(m.max_rel, 1e-6) << name << " depth " << depth;
      EXPECT_EQ(m.uncovered, 0) << name << " depth " << depth;
      EXPECT_EQ(m.unmatched, 0) << name << " depth " << depth;
      const Tessellation lt = run(accepted, depth, true);
      const conformance::FarLevel far_limit = far_level(accepted, kCC, depth, true);
      Match l = compare(lt, far_limit, depth, d, false);
      EXPECT_LE(l.max_rel, 1e-6) << name << " depth " << depth << " (limit)";
      conformance::FarLevel sided = far_limit;
      conformance::mark_sideless_normals(accepted, kCC, depth, sided);
      const Match n = compare(lt, sided, depth, d, true);
      l.max_deg = n.max_deg;
      shape.sideless += n.sideless;
      EXPECT_LE(l.max_deg, kNormalDeg) << name << " depth " << depth << " (normals)";
      EXPECT_EQ(count_open_edges(lt), boundary_edges(accepted) << depth) << name << " depth " << depth;
      if (closed) {
        const RayCrackReport cracks = ray_crack_check(lt, {50000, 50000, 1});
        EXPECT_EQ(cracks.cracks, 0) << name << " depth " << depth;
        shape.rays += cracks.rays, shape.cracks += cracks.cracks;
      }
      const Tessellation mt = run(accepted, depth, true, Backend::CpuMt);
      EXPECT_TRUE(mt.positions == lt.positions && mt.normals == lt.normals) << name << " depth " << depth << ": cpu-mt";
      shape.points += long(t.positions.size());
      shape.refined = std::max(shape.refined, m.max_rel), shape.limit = std::max(shape.limit, l.max_rel);
      shape.normal = std::max(shape.normal, l.max_deg);
      ++all.runs;
    }
    std::printf("  %-44s depths 1..%d  %ld points  refined %.2g  limit %.2g  normal %.2g deg (%ld sideless)  %ld rays, %ld cracks\n",
                name.c_str(), depth - 1, shape.points, shape.refined, shape.limit, shape.normal, shape.sideless, shape.rays,
                shape.cracks);
    all.refined = std::max(all.refined, shape.refined), all.limit = std::max(all.limit, shape.limit);
    all.normal = std::max(all.normal, shape.normal), all.rays += shape.rays, all.cracks += shape.cracks;
    all.points += shape.points, all.sideless += shape.sideless;
  }
  std::printf("edgefriend-cc: %d shapes, %d runs, %ld refined points, %d refused; worst refined %.2g, limit %.2g of the "
              "diagonal, normal %.2g deg (%ld sideless normals left out); %ld rays, %ld cracks\n",
              all.shapes, all.runs, all.points, all.refused, all.refined, all.limit, all.normal, all.sideless, all.rays, all.cracks);
}

// The built-ins without the corpus: a cube (valence 3), a creased cube (sharpness 2: the crease-to-
// smooth blend at depth 3), a torus (genus 1: V = Q), a quad sphere.
TEST(EdgeFriend, BuiltinsEqualFarRefinement) {
  for (const ControlMesh& mesh : {gen::cube(), gen::creased_cube(2.0f), gen::torus(8, 6), gen::quad_sphere(3)}) {
    const double d = bounds_of(mesh.positions).diagonal();
    for (int depth = 1; depth <= 4; ++depth) {
      const Match m = compare(run(mesh, depth, false), far_level(mesh, kCC, depth, false), depth, d, false);
      EXPECT_LE(m.max_rel, 1e-6) << mesh.name << " depth " << depth;
      EXPECT_EQ(m.uncovered, 0) << mesh.name << " depth " << depth;
      EXPECT_EQ(m.unmatched, 0) << mesh.name << " depth " << depth;
    }
  }
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

// Where a semi-sharp crease outlasts the depth the row says so (Far's masks take the sharpness
// left as infinite: not the limit there); once it has decayed, nothing is said.
TEST(EdgeFriend, SemiSharpnessLeftAtTheDepthIsNoted) {
  const ControlMesh cube = gen::creased_cube(2.0f);
  const SchemeInfo& info = find_scheme("edgefriend-cc")->info();
  for (int depth = 1; depth <= 3; ++depth) {
    auto e = edgefriend::make_evaluation(cube, default_request(info, Backend::Cpu, depth), true);
    const std::vector<std::string> notes = e->notes();
    const std::string note = notes.empty() ? "" : notes.front();
    if (depth < 2) EXPECT_NE(note.find("semi-sharp creases outlast depth 1"), std::string::npos) << note;
    else EXPECT_TRUE(note.empty()) << depth << ": " << note;
  }
}

}  // namespace
