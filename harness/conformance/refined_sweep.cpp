#include "harness/conformance/refined_sweep.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>

#include "harness/conformance/far_oracle.h"
#include "harness/conformance/limit_judge.h"
#include "harness/conformance/sweep_corpus.h"
#include "harness/core/errors.h"
#include "harness/mesh/facts.h"
#include "harness/reference/limit_evaluator.h"
#include "harness/validate/watertight.h"

namespace sdb::conformance {
namespace {

// Triangles of the level at `depth`: Loop's triangles split in four; Catmull-Clark's faces split
// into a quad a corner, then in four, two triangles a quad.
long triangles_at(const ControlMesh& m, SubdivisionRule rule, int depth) {
  if (rule == SubdivisionRule::Loop) return long(num_faces(m)) << (2 * depth);
  return 2L * long(m.face_vertices.size()) << (2 * depth - 2);
}

struct Totals {
  double refined = 0, limit = 0, normal = 0;
  size_t judged = 0, no_normal = 0, declared = 0, no_surface = 0;
  long rays = 0, cracks = 0;
  void add(const Totals& t) {
    refined = std::max(refined, t.refined), limit = std::max(limit, t.limit), normal = std::max(normal, t.normal);
    judged += t.judged, no_normal += t.no_normal, declared += t.declared, no_surface += t.no_surface;
    rays += t.rays, cracks += t.cracks;
  }
};

}  // namespace

void sweep_refined_peer(const RefinedPeer& peer, double max_deg) {
  const std::vector<std::string> shapes = sweep_shapes(peer.rule);
  if (shapes.empty()) GTEST_SKIP() << "no shared corpus";
  Totals all;
  int swept = 0, refused = 0, runs = 0, no_yardstick = 0;
  for (const std::string& name : shapes) {
    ControlMesh accepted;
    try {
      accepted = sweep_mesh(name, peer.rule, peer.scheme);
      peer.run(accepted, 1, false, Backend::Cpu);
    } catch (const InputError& e) {
      std::printf("  refused %s: %s\n", name.c_str(), e.what());
      ++refused;
      continue;
    }
    ++swept;
    const double d = bounds_of(accepted.positions).diagonal();
    const bool closed = compute_facts(accepted).closed;
    std::unique_ptr<LimitEvaluator> reference;
    try {
      reference = std::make_unique<LimitEvaluator>(accepted, peer.rule);
    } catch (const Unsupported& e) {
      std::printf("  no yardstick for %s: %s\n", name.c_str(), e.what());  // faces folded onto each other
      ++no_yardstick;
    }
    Totals shape;
    int depth = 1;
    for (; depth <= 5; ++depth) {
      if (depth > 1 && triangles_at(accepted, peer.rule, depth) > 400000) break;
      const Tessellation t = peer.run(accepted, depth, false, Backend::Cpu);
      const Match m = compare(t, far_level(accepted, peer.rule, depth, false), depth, d, false);
      EXPECT_LE(m.max_rel, 1e-6) << name << " depth " << depth;
      EXPECT_EQ(m.uncovered, 0) << name << " depth " << depth;
      EXPECT_EQ(m.unmatched, 0) << name << " depth " << depth;
      const Tessellation lt = peer.run(accepted, depth, true, Backend::Cpu);
      if (reference) {
        const LimitJudgement j = judge_against_limit(lt, *reference, d);
        EXPECT_LE(j.max_rel, 1e-6) << name << " depth " << depth << " (against the limit)";
        EXPECT_LE(j.max_deg, max_deg) << name << " depth " << depth << " (normal against the limit)";
        shape.limit = std::max(shape.limit, j.max_rel), shape.normal = std::max(shape.normal, j.max_deg);
        shape.judged += j.vertices, shape.no_normal += j.no_normal, shape.declared += j.declared;
        shape.no_surface += j.no_surface;
      } else {  // Far's limit masks, where Far's are the limit
        const Match l = compare(lt, far_level(accepted, peer.rule, depth, true), depth, d, false);
        EXPECT_LE(l.max_rel, 1e-6) << name << " depth " << depth << " (Far's limit)";
        shape.limit = std::max(shape.limit, l.max_rel);
      }
      EXPECT_EQ(count_open_edges(lt), boundary_edges(accepted) << depth) << name << " depth " << depth;
      if (closed) {
        const RayCrackReport cracks = ray_crack_check(lt, {50000, 50000, 1});
        EXPECT_EQ(cracks.cracks, 0) << name << " depth " << depth;
        shape.rays += cracks.rays, shape.cracks += cracks.cracks;
      }
      const Tessellation mt = peer.run(accepted, depth, true, Backend::CpuMt);
      EXPECT_TRUE(mt.positions == lt.positions && mt.normals == lt.normals) << name << " depth " << depth << ": cpu-mt";
      shape.refined = std::max(shape.refined, m.max_rel);
      ++runs;
    }
    std::printf("  %-44s depths 1..%d  refined %.2g  limit %.2g  normal %.2g deg at %zu vertices (%zu where the limit "
                "has no normal, %zu where the scheme gives none, %zu on faces with no limit surface)  %ld rays, %ld cracks\n",
                name.c_str(), depth - 1, shape.refined, shape.limit, shape.normal, shape.judged, shape.no_normal,
                shape.declared, shape.no_surface, shape.rays, shape.cracks);
    all.add(shape);
  }
  std::printf("%s: %d shapes (%d without a yardstick), %d runs, %d refused; worst refined %.2g, limit %.2g of the "
              "diagonal; normal %.2g deg at %zu vertices (%zu where the limit has none, %zu where the scheme gives "
              "none, %zu on faces with no surface); %ld rays, %ld cracks\n",
              peer.scheme.c_str(), swept, no_yardstick, runs, refused, all.refined, all.limit, all.normal, all.judged,
              all.no_normal, all.declared, all.no_surface, all.rays, all.cracks);
}

void expect_limit_is_exact(const RefinedPeer& peer, const ControlMesh& mesh, int depth) {
  const double d = bounds_of(mesh.positions).diagonal();
  const LimitEvaluator reference(mesh, peer.rule);
  const LimitJudgement j = judge_against_limit(peer.run(mesh, depth, true, Backend::Cpu), reference, d);
  EXPECT_LE(j.max_rel, 1e-6) << mesh.name << " depth " << depth;
  EXPECT_LE(j.max_deg, kExactNormalDeg) << mesh.name << " depth " << depth;
  EXPECT_EQ(j.declared, 0u) << mesh.name << " depth " << depth;
  std::printf("  %s depth %d: limit %.2g of the diagonal, normal %.2g deg at %zu vertices\n", mesh.name.c_str(), depth,
              j.max_rel, j.max_deg, j.vertices);
}

void expect_refined_equals_far(const RefinedPeer& peer, const ControlMesh& mesh) {
  const double d = bounds_of(mesh.positions).diagonal();
  for (int depth = 1; depth <= 4; ++depth) {
    const Match m = compare(peer.run(mesh, depth, false, Backend::Cpu), far_level(mesh, peer.rule, depth, false), depth, d, false);
    EXPECT_LE(m.max_rel, 1e-6) << mesh.name << " depth " << depth;
    EXPECT_EQ(m.uncovered, 0) << mesh.name << " depth " << depth;
    EXPECT_EQ(m.unmatched, 0) << mesh.name << " depth " << depth;
  }
}

}  // namespace sdb::conformance
