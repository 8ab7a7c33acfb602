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

// The fragments' limit positions are exact at every vertex where Far's masks are, and at darts
// and smooth valence-2 vertices too (ring_limit.h); Far's crease and corner position masks are
// exact at any valence (the crease curve and the corner do not depend on it). Left: vertices
// next to sharpness that outlasted the extra levels.
bool fragments_position_is_exact(const Far::TopologyLevel& l, int v) {
  if (l.IsVertexSemiSharp(v)) return false;
  for (int e : l.GetVertexEdges(v))
    if (l.IsEdgeSemiSharp(e)) return false;
  return true;
}

FarLevel osd_level(const ControlMesh& m, SubdivisionRule rule, int depth, bool limit) {
  return conformance::far_level(m, rule, depth, limit, [](const Far::TopologyLevel& l, int v) {
    return !fragments_position_is_exact(l, v);
  });
}

double angle_deg(const Point3& a, const Point3d& b) {
  // atan2 of |a x b| and a . b: acos of a dot this close to 1 cannot resolve 0.01 degrees.
  const double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  const double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  return std::atan2(std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), dot) * 180 / M_PI;
}

// Largest normal angle and distance (over the diagonal) from the reference limit, at every
// `stride`-th output vertex. Vertices whose limit the fragments do not take exactly (sharpness
// past the extra levels) are left out (counted in `special`), and so are reference normals of a
// degenerate parametrization (du parallel to dv: the corner of a smooth boundary, where the
// reference's du x dv has no direction).
std::pair<double, double> against_reference(const Tessellation& t, const LimitEvaluator& ref, const FarLevel& osd,
                                            int depth, double diagonal, size_t stride, long& special) {
  // Far's coords name one face per vertex; the copies in other faces' blocks are found by their
  // (bit-identical) position.
  std::map<Point3, int> by_position;
  for (size_t i = 0; i < t.positions.size(); ++i)
    if (auto it = osd.at.find(grid_key(t.coords[i], depth)); it != osd.at.end()) by_position[t.positions[i]] = it->second;
  double deg = 0, rel = 0;
  for (size_t i = 0; i < t.positions.size(); i += stride) {
    if (!ref.has_limit(static_cast<int>(t.coords[i].face))) continue;  // boundary rule "none"
    auto it = by_position.find(t.positions[i]);
    if (it == by_position.end() || osd.scheme_inexact[it->second]) {
      ++special;
      continue;
    }
    const LimitSample s = ref.evaluate(t.coords[i]);
    const double du = std::sqrt(s.du[0] * s.du[0] + s.du[1] * s.du[1] + s.du[2] * s.du[2]);
    const double dv = std::sqrt(s.dv[0] * s.dv[0] + s.dv[1] * s.dv[1] + s.dv[2] * s.dv[2]);
    const double c[3] = {s.du[1] * s.dv[2] - s.du[2] * s.dv[1], s.du[2] * s.dv[0] - s.du[0] * s.dv[2],
                         s.du[0] * s.dv[1] - s.du[1] * s.dv[0]};
    if (std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) < 1e-6 * du * dv) continue;
    // Where the reference has no normal to judge by (inexact_corner_normals in harness/reference:
    // a special vertex's own corner), positions only; RingLimit below judges those normals.
    const double n2 = s.normal[0] * s.normal[0] + s.normal[1] * s.normal[1] + s.normal[2] * s.normal[2];
    if (n2 > 0.25) deg = std::max(deg, angle_deg(t.normals[i], s.normal));
    const Point3& p = t.positions[i];
    rel = std::max(rel, std::sqrt((p[0] - s.position[0]) * (p[0] - s.position[0]) +
                                  (p[1] - s.position[1]) * (p[1] - s.position[1]) +
                                  (p[2] - s.position[2]) * (p[2] - s.position[2])) /
                            diagonal);
  }
  return {deg, rel};
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

// Chaikin creases and interior valence-2 vertices: Bfr is off there (the test below), so the
// limit is judged by Far's alone.
bool reference_is_right(const ControlMesh& m, SubdivisionRule rule) {
  if (m.crease_method == CreaseMethod::Chaikin) return false;
  auto r = make_refiner(m, rule);
  const Far::TopologyLevel& l = r->GetLevel(0);
  for (int v = 0; v < l.GetNumVertices(); ++v)
    if (!l.IsVertexBoundary(v) && l.GetVertexEdges(v).size() == 2) return false;
  return true;
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
      if (reference_is_right(accepted, rule)) reference = std::make_unique<LimitEvaluator>(accepted, rule);
    } catch (const Unsupported&) {
      // OpenSubdiv 3.5.0's Bfr defect (harness/reference/bfr_defect.h): no yardstick
    }
    int judged = 0;
    long special = 0, rays = 0, crack_count = 0;
    const bool closed = compute_facts(accepted).closed && accepted.holes.empty();
    Match worst;
    int depth = 1;
    for (; depth <= 5; ++depth) {
      const long blocks = num_faces(accepted) - static_cast<long>(accepted.holes.size());
      if (depth > 1 && blocks * (rule == SubdivisionRule::Loop ? 1L : 2L) << (2 * depth) > 400000) break;
      Tessellation t;
      try {
        t = run_fragments(accepted, rule, depth, false);
      } catch (const InputError& e) {
        std::printf("  refused %s: %s\n", name.c_str(), e.what());
        ++refused;
        break;
      }
      const Match m = compare(t, osd_level(accepted, rule, depth, false), depth, d, false);
      EXPECT_LE(m.max_rel, 1e-6) << name << " depth " << depth;
      EXPECT_EQ(m.uncovered, 0) << name << " depth " << depth;
      worst.max_rel = std::max(worst.max_rel, m.max_rel);
      // Projected from a deeper level where semi-sharp creases outlast the depth: the same grid
      // points of Far's limit at that level.
      const int inner = fragments::inner_depth_for(accepted, depth);
      const Tessellation lt = run_fragments(accepted, rule, depth, true);
      const FarLevel osd_limit = osd_level(accepted, rule, inner, true);
      const Match l = compare(lt, osd_limit, inner, d, false, true);
      EXPECT_LE(l.max_rel, 1e-6) << name << " depth " << depth << " (limit)";
      if (reference) {
        const auto [deg, rel] = against_reference(lt, *reference, osd_limit, inner, d, 7, special);
        EXPECT_LE(deg, 0.01) << name << " depth " << depth << " (normal against the reference)";
        EXPECT_LE(rel, 1e-5) << name << " depth " << depth << " (against the reference)";
        worst.max_deg = std::max(worst.max_deg, deg);
        ++judged;
      }
      EXPECT_EQ(count_open_edges(t), boundary_edges(accepted) << depth) << name << " depth " << depth;
      if (closed) {
        const RayCrackReport cracks = ray_crack_check(lt, {50000, 50000, 1});
        EXPECT_EQ(cracks.cracks, 0) << name << " depth " << depth << " (" << cracks.rays << " rays)";
        rays += cracks.rays, crack_count += cracks.cracks;
      }
    }
    std::printf("  %-44s depths 1..%d  refined %.2g  normal %.2g deg from the reference at %d depths (%ld special)"
                "  %ld rays, %ld cracks\n", name.c_str(), depth - 1, worst.max_rel, worst.max_deg, judged, special, rays,
                crack_count);
    exact += worst.max_rel <= 1e-6;
  }
  std::printf("%s: %d shapes exact, %d refused\n", info.name.c_str(), exact, refused);
}

TEST(FragmentsSweep, CatmullClarkCorpusEqualsFarRefinement) { sweep(SubdivisionRule::CatmullClark); }
TEST(FragmentsSweep, LoopCorpusEqualsFarRefinement) { sweep(SubdivisionRule::Loop); }

}  // namespace
namespace {

// Where the reference (Bfr) and Far's limit masks disagree, the fragments' limit (Far's) is the
// one Far's depth-8 refined points converge to: Bfr in OpenSubdiv 3.5.0 is off by 3.5e-4 of the
// diagonal on Chaikin creases and by 0.8% next to interior valence-2 vertices (README.md).
TEST(FragmentsSweep, WhereTheReferenceDisagreesFarsLimitIsTheLimit) {
  for (const char* name : {"opensubdiv/catmark_chaikin1", "opensubdiv/catmark_val2_foldover"}) {
    if (!corpus_has(name)) GTEST_SKIP() << "no shared corpus";
    const ControlMesh m = accept_mesh(load_mesh(name), find_scheme("fragments-cc")->info());
    const double d = bounds_of(m.positions).diagonal();
    const LimitEvaluator ref(m, SubdivisionRule::CatmullClark);
    const int depth = 5, deep = 8;
    const Tessellation t = run_fragments(m, SubdivisionRule::CatmullClark, depth, true);
    const FarLevel fine = osd_level(m, SubdivisionRule::CatmullClark, deep, false);
    double ours = 0, bfr = 0;
    for (size_t k = 0; k < t.positions.size(); ++k) {
      const SurfaceCoord& c = t.coords[k];
      auto it = fine.at.find(grid_key(c, deep));
      if (it == fine.at.end()) continue;
      const LimitSample s = ref.evaluate(c);
      const Point3 b = {float(s.position[0]), float(s.position[1]), float(s.position[2])};
      if (distance(t.positions[k], b) / d < 1e-4) continue;
      ours = std::max(ours, distance(t.positions[k], fine.points[it->second]) / d);
      bfr = std::max(bfr, distance(b, fine.points[it->second]) / d);
    }
    std::printf("%s: where they disagree, ours lies %.2g from Far's depth-8 points, the reference %.2g\n", name, ours,
                bfr);
    EXPECT_LT(ours, 5e-5) << name;
    EXPECT_GT(bfr, 10 * ours) << name;
  }
}

}  // namespace
