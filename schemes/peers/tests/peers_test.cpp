// The peers against the reference and each other (what harness/reference/README.md reports).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <tuple>

#include "datasets/generators.h"
#include "datasets/manifest.h"
#include "harness/bench/measure.h"
#include "harness/core/errors.h"
#include "harness/mesh/acceptance.h"
#include "harness/mesh/facts.h"
#include "harness/mesh/placement.h"
#include "harness/mesh/quadrangulate.h"
#include "harness/reference/limit_evaluator.h"
#include "harness/validate/deviation.h"
#include "harness/validate/watertight.h"
#include "schemes/peers/peers.h"

using namespace sdb;

namespace {

const Scheme& peer(const std::string& name) {
  static const auto peers = make_peer_schemes();
  for (const auto& p : peers)
    if (p->info().name == name) return *p;
  throw std::logic_error("no peer " + name);
}

Tessellation run_peer(const std::string& name, const ControlMesh& mesh, int level, Backend b = Backend::Cpu) {
  const Scheme& s = peer(name);
  const ControlMesh accepted = accept_mesh(mesh, s.info());
  auto e = s.prepare(accepted, {b, level, 0, Parameters::defaults(s.info().parameters)});
  e->execute();
  Tessellation t = e->result();
  if (!t.reference) t.reference = std::make_shared<ControlMesh>(accepted);
  return t;
}

bool corpus_present() { return corpus_dir().has_value(); }

double diag(const ControlMesh& m) { return bounds_of(m.positions).diagonal(); }

}  // namespace

// On an all-regular mesh the limit is a bicubic B-spline: the three peers and the reference agree
// to float precision at the same SurfaceCoord.
TEST(Peers, AgreeWithTheReferenceOnTheRegularTorus) {
  const ControlMesh torus = gen::torus(12, 20);
  const LimitEvaluator ref(torus, SubdivisionRule::CatmullClark);
  for (const auto& [name, level] : std::vector<std::pair<std::string, int>>{
           {"osd-uniform", 3}, {"osd-bfr", 9}, {"embree-subdiv", 9}}) {
    const DeviationReport d = measure_deviation(run_peer(name, torus, level), ref);
    EXPECT_LE(d.pos_max_rel_diag, 1e-5) << name;
    EXPECT_LE(d.normal_max_deg, 1e-2) << name;
    EXPECT_GT(d.vertices, 0) << name;
  }
}

// Uniform refinement tracks SurfaceCoords through n-gon sub-faces and triangles (Spot has both):
// osd-uniform's limit points sit on the reference at their coords.
TEST(Peers, UniformCoordsLandOnTheLimitOfSpot) {
  if (!corpus_present()) GTEST_SKIP() << "shared corpus not found beside the checkout";
  const ControlMesh spot = load_mesh("crane/spot_control");
  const LimitEvaluator ref(spot, SubdivisionRule::CatmullClark);
  for (int level : {1, 2, 3}) {
    const DeviationReport d = measure_deviation(run_peer("osd-uniform", spot, level), ref);
    EXPECT_LE(d.pos_max_rel_diag, 1e-5) << "level " << level;
    EXPECT_LE(d.normal_max_deg, 0.05) << "level " << level;
  }
  // osd-bfr evaluates the n-gons through Bfr's sub-face parametrization: same surface.
  const DeviationReport b = measure_deviation(run_peer("osd-bfr", spot, 5), ref);
  EXPECT_LE(b.pos_max_rel_diag, 1e-4);
}

TEST(Peers, LoopUniformMatchesTheLoopLimit) {
  const ControlMesh ico = gen::icosphere(1);
  const LimitEvaluator ref(ico, SubdivisionRule::Loop);
  const DeviationReport d = measure_deviation(run_peer("osd-uniform-loop", ico, 3), ref);
  EXPECT_LE(d.pos_max_rel_diag, 1e-5);
  EXPECT_LE(d.normal_max_deg, 0.05);
}

// Uniform refinement + PrimvarRefiner::Limit is exact only once the depth exceeds every
// semi-sharp crease (Far's limit masks treat sharpness left at the last level as infinite); these
// shapes have sharpness up to 5, so depth 6.
TEST(Peers, OsdUniformHonoursCreasesAndHolesBeyondTheirSharpness) {
  if (!corpus_present()) GTEST_SKIP() << "shared corpus not found beside the checkout";
  for (const char* name : {"opensubdiv/catmark_cube_creases1", "opensubdiv/catmark_hole_test1",
                           "opensubdiv/catmark_edgecorner", "opensubdiv/catmark_cube_corner4"}) {
    const ControlMesh m = load_mesh(name);
    EXPECT_LE(measure_deviation(run_peer("osd-uniform", m, 6), LimitEvaluator(m, SubdivisionRule::CatmullClark))
                  .pos_max_rel_diag,
              1e-5)
        << name;
  }
  // Below that depth the peer's error is real and large: the reason for the rule above.
  const ControlMesh creased = load_mesh("opensubdiv/catmark_cube_creases1");
  EXPECT_GT(measure_deviation(run_peer("osd-uniform", creased, 3), LimitEvaluator(creased, SubdivisionRule::CatmullClark))
                .pos_max_rel_diag,
            1e-3);
  // Chaikin creases: Far's uniform path and Bfr disagree by a steady ~4.5e-4 of the diagonal at
  // depths 5..7 (measured). Kept as a bound, reported in README. Bfr is not the limit there either
  // (5.2e-4 off Far's refinement next to the corners the creases meet): osd-bfr refuses the mesh.
  const ControlMesh chaikin = load_mesh("opensubdiv/catmark_chaikin1");
  const LimitEvaluator ref(chaikin, SubdivisionRule::CatmullClark);
  EXPECT_LE(measure_deviation(run_peer("osd-uniform", chaikin, 6), ref).pos_max_rel_diag, 1e-3);
  EXPECT_THROW(run_peer("osd-bfr", chaikin, 9), Unsupported);
}

// Issue 39: below the largest semi-sharp crease's sharpness a row of osd-uniform(-loop) says it
// approximates the limit, shows by how much and is not failed by the bound its reproducing rows
// keep; from that depth on it reproduces the limit and the bound judges it (osd-uniform-loop's).
TEST(Peers, OsdUniformApproximatesWhereACreaseOutlastsTheDepthAndSaysSo) {
  MeasureContext context{MachineInfo{}};
  MeasureOptions options;
  options.time = false;
  options.rays = 1000;
  // The creased cube: every edge of sharpness 2.
  for (int depth : {1, 2}) {
    const RunRow row = measure_run({"osd-uniform", "creased-cube", Backend::Cpu, depth}, options, context);
    std::printf("  osd-uniform creased-cube depth %d: %s, max %.3g p95 %.3g of the diagonal, %s\n", depth, row.limit.c_str(),
                row.deviation.pos_max_rel_diag, row.deviation.pos_p95_rel_diag, to_string(row.status).data());
    EXPECT_EQ(row.limit, depth < 2 ? "approximates" : "reproduces");
    EXPECT_EQ(row.status, RunStatus::Ok) << row.message;
    if (depth < 2) {
      EXPECT_GT(row.deviation.pos_max_rel_diag, 1e-3) << "the approximation is shown as it is";
    } else {
      EXPECT_LE(row.deviation.pos_max_rel_diag, 1e-5);
    }
  }
  if (!corpus_present()) GTEST_SKIP() << "shared corpus not found beside the checkout";
  // Semi-sharp creases of sharpness 2.8 on a Loop cube: osd-uniform-loop's bound (1e-5) would fail
  // depths 1 and 2; at 3 it applies.
  for (int depth : {1, 2, 3}) {
    const RunRow row = measure_run({"osd-uniform-loop", "opensubdiv/loop_cube_creases0", Backend::Cpu, depth}, options, context);
    std::printf("  osd-uniform-loop loop_cube_creases0 depth %d: %s, max %.3g p95 %.3g of the diagonal, bound %g, %s %s\n",
                depth, row.limit.c_str(), row.deviation.pos_max_rel_diag, row.deviation.pos_p95_rel_diag,
                row.bound.pos_rel_diag, to_string(row.status).data(), row.message.c_str());
    EXPECT_EQ(row.limit, depth < 3 ? "approximates" : "reproduces");
    EXPECT_EQ(row.bound.pos_rel_diag < 0, depth < 3) << "the bound judges the rows that reproduce";
    if (depth < 3) {
      EXPECT_EQ(row.status, RunStatus::Ok) << row.message;
    }
  }
}

// osd-bfr raises Bfr's approximation level to what its rate samples, so it lands on the limit
// even next to high-valence vertices (Bfr's default level 2 misses by up to 1e-2 of the diagonal).
// The bound is float evaluation (1.5e-6 measured at valence 64) under the 1e-5 used throughout.
TEST(Peers, OsdBfrIsExactAtItsSamplesNearExtraordinaryVertices) {
  if (!corpus_present()) GTEST_SKIP() << "shared corpus not found beside the checkout";
  for (const char* name : {"opensubdiv/catmark_hole_test1", "opensubdiv/catmark_pole64", "crane/blub_control"})
    for (int rate : {5, 17, 33}) {
      const ControlMesh m = load_mesh(name);
      EXPECT_LE(measure_deviation(run_peer("osd-bfr", m, rate), LimitEvaluator(m, SubdivisionRule::CatmullClark))
                    .pos_max_rel_diag,
                1e-5)
          << name << " N=" << rate;
    }
}

// The anchors' verdicts on every OpenSubdiv regression shape, Catmull-Clark and Loop, at rates 5,
// 9 and 17 (issue 39): positions and normals within the scheme's own bound at every vertex, or the
// mesh refused up front with the reason (prepare's Unsupported). The vertices where the scheme
// gives no normal (its zero normal: infinitely sharp corners, degenerate tangents) are counted
// and printed, per shape where there are any. Before issue 39c: darts left at the rate's
// approximation level (loop_cubes_infsharp 4.8e-5 of the diagonal, catmark_inf_crease1 2.5e-4),
// Bfr's level-10 normal at infinitely sharp corners (5.63 and 7.02 degrees) and parallel tangents
// taken for a normal (loop_saddle_edgeonly 45 degrees, catmark_cube_creases2 180).
TEST(OsdBfr, WithinItsBoundOrRefusedOnEveryOpenSubdivShape) {
  if (!corpus_present()) GTEST_SKIP() << "shared corpus not found beside the checkout";
  for (const char* scheme : {"osd-bfr", "osd-bfr-loop"}) {
    const bool loop = std::string(scheme) == "osd-bfr-loop";
    const SubdivisionRule rule = loop ? SubdivisionRule::Loop : SubdivisionRule::CatmullClark;
    const DeviationBound bound = peer(scheme).info().bound;
    long ok = 0, refused = 0, no_yardstick = 0, vertices = 0, declared = 0;
    for (const auto& e : list_meshes()) {
      if (e.kind != "corpus" || e.name.rfind(loop ? "opensubdiv/loop_" : "opensubdiv/catmark_", 0) != 0) continue;
      const ControlMesh m = placed_mesh(load_mesh(e.name));
      for (int rate : {5, 9, 17}) {
        Tessellation t;
        try {
          t = run_peer(scheme, m, rate);
        } catch (const Unsupported& u) {
          ++refused;
          EXPECT_NE(std::string(u.what()).find(m.source), std::string::npos) << e.name << ": a refusal names the file";
          continue;
        }
        std::unique_ptr<LimitEvaluator> ref;
        try {
          ref = std::make_unique<LimitEvaluator>(m, rule);
        } catch (const Unsupported&) {
          ++no_yardstick;  // folded faces: reference_test holds that refusal
          continue;
        }
        const DeviationReport d = measure_deviation(t, *ref);
        EXPECT_LE(d.pos_max_rel_diag, bound.pos_rel_diag) << scheme << " " << e.name << " N=" << rate;
        EXPECT_LE(d.normal_max_deg, bound.normal_deg) << scheme << " " << e.name << " N=" << rate;
        EXPECT_GT(d.vertices, 0) << scheme << " " << e.name << " N=" << rate;
        ++ok;
        vertices += d.vertices;
        declared += d.normal_declared;
        if (d.normal_declared > 0)
          std::printf("  %s %s N=%d: no normal given at %ld of %ld vertices\n", scheme, e.name.c_str(), rate,
                      d.normal_declared, d.vertices);
      }
    }
    std::printf("%s: %ld runs judged (%ld vertices, %ld without a normal given), %ld refused, %ld without a "
                "yardstick\n", scheme, ok, vertices, declared, refused, no_yardstick);
    EXPECT_GE(ok, loop ? 60 : 180) << scheme;
  }
}

// One thread against all, closed inputs giving closed surfaces: the conformance suite
// (conformance_test.cpp) checks them for every peer.

namespace {

// The largest distance between two tessellations at the SurfaceCoords they share, over the
// diagonal (depth 3 and rate 9 sample the same ptex points: multiples of 1/8).
double mutual_distance(const Tessellation& a, const Tessellation& b, const ControlMesh& mesh, long* shared) {
  std::map<std::tuple<uint32_t, float, float>, Point3> at;
  for (size_t i = 0; i < a.coords.size(); ++i) at[{a.coords[i].face, a.coords[i].u, a.coords[i].v}] = a.positions[i];
  double worst = 0;
  *shared = 0;
  for (size_t i = 0; i < b.coords.size(); ++i) {
    auto it = at.find({b.coords[i].face, b.coords[i].u, b.coords[i].v});
    if (it == at.end()) continue;
    ++*shared;
    double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += std::pow(double(it->second[k]) - b.positions[i][k], 2);
    worst = std::max(worst, std::sqrt(d2));
  }
  return worst / diag(mesh);
}

}  // namespace

// Issue 3: osd-uniform and osd-bfr agree with each other at matching SurfaceCoords: to float
// precision on the regular torus, and on Spot (quadrangulated) to the measured 1e-6 of the
// diagonal (measured 1.4e-7 over 46,850 shared points; both exact there up to float).
TEST(Peers, UniformAndBfrAgreeAtMatchingSurfaceCoords) {
  long shared = 0;
  const ControlMesh torus = gen::torus(12, 20);
  EXPECT_LE(mutual_distance(run_peer("osd-uniform", torus, 3), run_peer("osd-bfr", torus, 9), torus, &shared), 1e-5);
  EXPECT_EQ(shared, 12 * 20 * 81 - 12 * 20 * (81 - 64)) << "every uniform vertex has a Bfr twin";
  if (!corpus_present()) GTEST_SKIP() << "shared corpus not found beside the checkout";
  const ControlMesh spot = quadrangulate(load_mesh("crane/spot_control"));
  const double d = mutual_distance(run_peer("osd-uniform", spot, 3), run_peer("osd-bfr", spot, 9), spot, &shared);
  std::printf("osd-uniform depth 3 vs osd-bfr N=9 on quadrangulated Spot: %.3g of the diagonal over %ld points\n", d, shared);
  EXPECT_GT(shared, 40000);
  EXPECT_LE(d, 1e-6);
}
