// Mesh fragments against OpenSubdiv:
//   - before limit projection, every refined point at depths 1..5 equals Far's uniform refinement
//     of the same mesh (matched through the ptex grid point it stands for), on the corpus sweep;
//   - after it, every output vertex equals osd-uniform's limit projection (PrimvarRefiner::Limit);
//   - exact welding closes every closed input and leaves exactly the input's boundary open, and
//     100,000 rays (half aimed at face borders) find no crack in any closed one.
#include <gtest/gtest.h>

#include <opensubdiv/far/primvarRefiner.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <tuple>

#include "datasets/generators.h"
#include "datasets/manifest.h"
#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/mesh/acceptance.h"
#include "harness/mesh/facts.h"
#include "harness/mesh/osd_topology.h"
#include "harness/reference/limit_evaluator.h"
#include "harness/reference/surface_normal.h"
#include "harness/reference/uniform_coords.h"
#include "harness/validate/watertight.h"
#include "schemes/fragments/fragments.h"
#include "schemes/fragments/surface.h"
#include "harness/conformance/far_oracle.h"
#include "harness/conformance/limit_judge.h"
#include "harness/conformance/sweep_corpus.h"

using namespace sdb;

namespace {

namespace Far = OpenSubdiv::Far;
using conformance::boundary_edges;
using conformance::compare;
using conformance::distance;
using conformance::FarLevel;
using conformance::grid_key;
using conformance::Match;
using conformance::sweep_shapes;

const char* scheme_name(SubdivisionRule rule) {
  return rule == SubdivisionRule::Loop ? "fragments-loop" : "fragments-cc";
}

Tessellation run_fragments(const ControlMesh& accepted, SubdivisionRule rule, int depth, bool limit,
                           Backend backend = Backend::Cpu) {
  const SchemeInfo& info = find_scheme(scheme_name(rule))->info();
  auto e = fragments::make_evaluation(accepted, rule, default_request(info, backend, depth), limit);
  e->execute();
  return e->result();
}

FarLevel osd_level(const ControlMesh& m, SubdivisionRule rule, int depth, bool limit) {
  return conformance::far_level(m, rule, depth, limit);
}

double angle_deg(const Point3& a, const Point3d& b) {
  // atan2 of |a x b| and a . b: acos of a dot this close to 1 cannot resolve 0.01 degrees.
  const double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  const double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  return std::atan2(std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), dot) * 180 / M_PI;
}

TEST(Fragments, RegularTorusEqualsFarRefinementAndLimit) {
  const ControlMesh torus_mesh = gen::torus(8, 6);
  const double d = bounds_of(torus_mesh.positions).diagonal();
  for (int depth = 1; depth <= 3; ++depth) {
    const Match refined = compare(run_fragments(torus_mesh, SubdivisionRule::CatmullClark, depth, false),
                                  osd_level(torus_mesh, SubdivisionRule::CatmullClark, depth, false), depth, d, false);
    EXPECT_LE(refined.max_rel, 1e-6) << depth;
    EXPECT_EQ(refined.uncovered, 0);
    const Match limit = compare(run_fragments(torus_mesh, SubdivisionRule::CatmullClark, depth, true),
                                osd_level(torus_mesh, SubdivisionRule::CatmullClark, depth, true), depth, d, true);
    EXPECT_LE(limit.max_rel, 1e-6) << depth;
    EXPECT_LE(limit.max_deg, 0.01) << depth;
  }
}

TEST(Fragments, CubeAndIcosphere) {
  for (SubdivisionRule rule : {SubdivisionRule::CatmullClark, SubdivisionRule::Loop}) {
    const ControlMesh m = rule == SubdivisionRule::Loop ? gen::icosphere(1) : gen::cube();
    const double d = bounds_of(m.positions).diagonal();
    for (int depth = 1; depth <= 4; ++depth) {
      const Tessellation t = run_fragments(m, rule, depth, false);
      const Match refined = compare(t, osd_level(m, rule, depth, false), depth, d, false);
      EXPECT_LE(refined.max_rel, 1e-6) << depth;
      EXPECT_EQ(refined.uncovered, 0);
      EXPECT_EQ(count_open_edges(t), 0) << depth;
      const Match limit = compare(run_fragments(m, rule, depth, true), osd_level(m, rule, depth, true), depth, d, true);
      EXPECT_LE(limit.max_rel, 1e-6) << depth;
      EXPECT_LE(limit.max_deg, 0.01) << depth;
    }
  }
}

// The point an output vertex stands for, independent of where its face's vertex list starts:
// each corner's global vertex with its bilinear (quad) or barycentric (triangle) weight, in units
// of 4^-depth, sorted.
using PointKey = std::vector<std::pair<int, long>>;
PointKey point_key(const ControlMesh& m, const std::vector<int>& offsets, const SurfaceCoord& c, int depth) {
  const long s = 1L << depth, i = std::lround(c.u * s), j = std::lround(c.v * s);
  const int* fv = m.face_vertices.data() + offsets[c.face];
  PointKey k;
  if (m.face_sizes[c.face] == 3) {
    k = {{fv[0], (s - i - j) * s}, {fv[1], i * s}, {fv[2], j * s}};
  } else {
    k = {{fv[0], (s - i) * (s - j)}, {fv[1], i * (s - j)}, {fv[2], i * j}, {fv[3], (s - i) * j}};
  }
  std::sort(k.begin(), k.end());
  return k;
}

// Nets are built in a canonical rotation (net.cpp), so a mesh whose faces start their vertex
// lists at other corners has the same shapes, and every point of its surface the same bits.
TEST(Fragments, WhereEachFaceStartsChangesNeitherShapesNorPoints) {
  for (SubdivisionRule rule : {SubdivisionRule::CatmullClark, SubdivisionRule::Loop}) {
    const ControlMesh m = rule == SubdivisionRule::Loop ? gen::icosphere(1) : gen::cube();
    ControlMesh turned = m;
    const std::vector<int> offsets = face_offsets(m);
    for (size_t f = 0; f < m.face_sizes.size(); ++f) {
      int* fv = turned.face_vertices.data() + offsets[f];
      std::rotate(fv, fv + (f * 7 + 1) % m.face_sizes[f], fv + m.face_sizes[f]);
    }
    const int depth = 3;
    EXPECT_EQ(fragments::FragmentSurface(m, rule, depth, depth).tables.size(),
              fragments::FragmentSurface(turned, rule, depth, depth).tables.size());
    const Tessellation a = run_fragments(m, rule, depth, true), b = run_fragments(turned, rule, depth, true);
    std::map<PointKey, size_t> in_b;
    for (size_t i = 0; i < b.coords.size(); ++i) in_b[point_key(turned, offsets, b.coords[i], depth)] = i;
    size_t matched = 0;
    double deg = 0;
    for (size_t i = 0; i < a.coords.size(); ++i) {
      auto it = in_b.find(point_key(m, offsets, a.coords[i], depth));
      if (it == in_b.end()) continue;
      ++matched;
      EXPECT_EQ(a.positions[i], b.positions[it->second]) << i;
      deg = std::max(deg, angle_deg(a.normals[i], {b.normals[it->second][0], b.normals[it->second][1],
                                                   b.normals[it->second][2]}));
    }
    EXPECT_EQ(matched, a.coords.size());
    EXPECT_LE(deg, 1e-4);
  }
}

// Depths 1..5, as far as the output stays small enough for a test (depth 1 always).
void sweep(SubdivisionRule rule) {
  const std::vector<std::string> shapes = sweep_shapes(rule);
  if (shapes.empty()) GTEST_SKIP() << "no shared corpus";
  const SchemeInfo& info = find_scheme(scheme_name(rule))->info();
  int exact = 0, refused = 0;
  for (const std::string& name : shapes) {
    ControlMesh accepted;
    try {
      accepted = conformance::sweep_mesh(name, rule, scheme_name(rule));
    } catch (const InputError& e) {
      std::printf("  refused %s: %s\n", name.c_str(), e.what());
      ++refused;
      continue;
    }
    const double d = bounds_of(accepted.positions).diagonal();
    std::unique_ptr<LimitEvaluator> reference;
    try {
      reference = std::make_unique<LimitEvaluator>(accepted, rule);
    } catch (const Unsupported& e) {
      std::printf("  no yardstick for %s: %s\n", name.c_str(), e.what());  // faces folded onto each other
    }
    long rays = 0, crack_count = 0;
    size_t judged = 0, no_normal = 0, no_surface = 0, declared = 0;
    const bool closed = compute_facts(accepted).closed && accepted.holes.empty();
    Match worst;
    conformance::LimitJudgement limit;
    int depth = 1;
    for (; depth <= 5; ++depth) {
      const long blocks = num_faces(accepted) - static_cast<long>(accepted.holes.size());
      if (depth > 1 && blocks * (rule == SubdivisionRule::Loop ? 1L : 2L) << (2 * depth) > 400000) break;
      Tessellation t, lt;
      try {
        t = run_fragments(accepted, rule, depth, false);
        lt = run_fragments(accepted, rule, depth, true);
      } catch (const std::exception& e) {  // a refusal the scheme gives up front, with its reason
        if (!dynamic_cast<const Unsupported*>(&e) && !dynamic_cast<const InputError*>(&e)) throw;
        std::printf("  refused %s depth %d: %s\n", name.c_str(), depth, e.what());
        ++refused;
        break;
      }
      const Match m = compare(t, osd_level(accepted, rule, depth, false), depth, d, false);
      EXPECT_LE(m.max_rel, 1e-6) << name << " depth " << depth;
      EXPECT_EQ(m.uncovered, 0) << name << " depth " << depth;
      worst.max_rel = std::max(worst.max_rel, m.max_rel);
      // Every output vertex against the limit (the yardstick), its normal on its face's side.
      if (reference) {
        const conformance::LimitJudgement j = conformance::judge_against_limit(lt, *reference, d);
        EXPECT_LE(j.max_rel, 1e-5) << name << " depth " << depth << " (against the limit)";
        EXPECT_LE(j.max_deg, 0.01) << name << " depth " << depth << " (normal against the limit)";
        limit.max_rel = std::max(limit.max_rel, j.max_rel), limit.max_deg = std::max(limit.max_deg, j.max_deg);
        judged += j.vertices, no_normal += j.no_normal, no_surface += j.no_surface, declared += j.declared;
      }
      EXPECT_EQ(count_open_edges(t), boundary_edges(accepted) << depth) << name << " depth " << depth;
      if (closed) {
        const RayCrackReport cracks = ray_crack_check(lt, {50000, 50000, 1});
        EXPECT_EQ(cracks.cracks, 0) << name << " depth " << depth << " (" << cracks.rays << " rays)";
        rays += cracks.rays, crack_count += cracks.cracks;
      }
    }
    std::printf("  %-44s depths 1..%d  refined %.2g  limit %.2g, normal %.2g deg at %zu vertices (%zu where the limit "
                "has no normal, %zu where the scheme gives none, %zu on faces with no limit surface)  %ld rays, %ld cracks\n", name.c_str(), depth - 1, worst.max_rel, limit.max_rel,
                limit.max_deg, judged, no_normal, declared, no_surface, rays, crack_count);
    exact += worst.max_rel <= 1e-6;
  }
  std::printf("%s: %d shapes exact, %d refused\n", info.name.c_str(), exact, refused);
}

TEST(FragmentsSweep, CatmullClarkCorpusEqualsFarRefinement) { sweep(SubdivisionRule::CatmullClark); }
TEST(FragmentsSweep, LoopCorpusEqualsFarRefinement) { sweep(SubdivisionRule::Loop); }

}  // namespace
