// The yardstick: LimitEvaluator's accuracy and the dense limit tessellation.
#include <gtest/gtest.h>

#include <opensubdiv/far/primvarRefiner.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "datasets/generators.h"
#include "datasets/manifest.h"
#include "harness/core/errors.h"
#include "harness/mesh/facts.h"
#include "harness/mesh/osd_topology.h"
#include "harness/mesh/quadrangulate.h"
#include "harness/reference/bfr_defect.h"
#include "harness/reference/dense_limit.h"
#include "harness/reference/limit_evaluator.h"
#include "harness/reference/uniform_coords.h"
#include "harness/reference/vertex_limit.h"
#include "harness/validate/deviation.h"
#include "harness/validate/watertight.h"

using namespace sdb;

namespace {

bool corpus_present() { return corpus_dir().has_value(); }

double diag(const ControlMesh& m) { return bounds_of(m.positions).diagonal(); }

}  // namespace

// The reference near extraordinary vertices: Bfr refines irregular faces towards the corner to
// the approximation level L. Levels 9 and 10 must agree to double precision at the corner and at
// ptex distance >= 2^-8 from it (every sample a scheme takes); inside, the residual is bounded.
TEST(LimitEvaluator, ApproximationLevelsAgreeAwayFromTheExtraordinaryCorner) {
  std::vector<ControlMesh> meshes = {gen::pole(7), gen::pole(3)};
  if (corpus_present()) meshes.push_back(load_mesh("opensubdiv/catmark_pole64"));
  for (const ControlMesh& m : meshes) {
    const LimitEvaluator fine(m, SubdivisionRule::CatmullClark, {10, 10});
    const LimitEvaluator coarse(m, SubdivisionRule::CatmullClark, {9, 9});
    double outside = 0, inside = 0;
    for (int f = 0; f < fine.num_ptex_faces(); ++f)
      for (float t : {0.0f, 1.0f / 1024, 1.0f / 512, 1.0f / 256, 1.0f / 64, 0.25f})
        for (const auto& [u, v] : {std::pair{t, 0.0f}, std::pair{t, t}, std::pair{1 - t, 1 - t}, std::pair{0.0f, 1 - t}}) {
          const auto a = fine.evaluate({uint32_t(f), u, v}), b = coarse.evaluate({uint32_t(f), u, v});
          double& worst = (t == 0 || t >= 1.0f / 256) ? outside : inside;
          for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(a.position[k] - b.position[k]));
        }
    EXPECT_LE(outside / diag(m), 1e-12) << m.name;
    EXPECT_LE(inside / diag(m), 1e-3) << m.name;
  }
}

// Derivatives are with respect to ptex (u,v), also on the sub-faces of n-gons.
TEST(LimitEvaluator, DerivativesMatchFiniteDifferencesOnNgonSubfaces) {
  ControlMesh m = gen::cube();
  // Two pentagons: the midpoint of edge (0,1) inserted into both faces that share it.
  m.positions.push_back({0, -1, -1});
  m.face_sizes = {5, 4, 5, 4, 4, 4};
  m.face_vertices = {0, 3, 2, 1, 8, 4, 5, 6, 7, 0, 8, 1, 5, 4, 2, 3, 7, 6, 1, 2, 6, 5, 3, 0, 4, 7};
  ASSERT_TRUE(compute_facts(m).closed);
  const LimitEvaluator ref(m, SubdivisionRule::CatmullClark);
  ASSERT_EQ(ref.num_ptex_faces(), 5 + 1 + 5 + 1 + 1 + 1);
  const double h = 1e-5;
  for (int f = 0; f < ref.num_ptex_faces(); ++f) {
    const SurfaceCoord c{uint32_t(f), 0.4f, 0.3f};
    const auto s = ref.evaluate(c);
    const auto su = ref.evaluate({c.face, float(c.u + h), c.v}), sv = ref.evaluate({c.face, c.u, float(c.v + h)});
    const double hu = double(float(c.u + h)) - c.u, hv = double(float(c.v + h)) - c.v;
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR((su.position[k] - s.position[k]) / hu, s.du[k], 1e-2) << "ptex " << f;
      EXPECT_NEAR((sv.position[k] - s.position[k]) / hv, s.dv[k], 1e-2) << "ptex " << f;
    }
  }
}

// The Hausdorff yardstick: a closed mesh gives a closed dense surface (shared layout), lying on
// the limit it stands for, for Catmull-Clark and Loop alike.
TEST(DenseLimit, IsClosedAndOnTheLimitForBothRules) {
  for (const auto& [mesh, rule] : std::vector<std::pair<ControlMesh, SubdivisionRule>>{
           {gen::pole(5), SubdivisionRule::CatmullClark}, {gen::icosphere(1), SubdivisionRule::Loop}}) {
    const LimitEvaluator limit(mesh, rule);
    const DenseLimit dense = dense_limit(limit);
    const long s = dense_limit_segments(num_faces(mesh));
    EXPECT_EQ(dense.surface.num_triangles(), size_t(num_faces(mesh) * s * s * (rule == SubdivisionRule::Loop ? 1 : 2)));
    EXPECT_EQ(count_open_edges(dense.surface), 0);
    EXPECT_LE(measure_deviation(dense.surface, limit).pos_max_rel_diag, 1e-6);
  }
}

// The oracle's points: Far's uniform refinement of the whole mesh to the grid's level, in double.
struct GridLevel {
  std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> refiner;
  std::vector<Point3d> points;  // of level `level`
  std::vector<SurfaceCoord> corners;  // per face corner of that level (uniform_face_corner_coords)
};

struct DoublePoint {
  double p[3];
  void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0; }
  void AddWithWeight(const DoublePoint& s, double w) {
    for (int k = 0; k < 3; ++k) p[k] += w * s.p[k];
  }
};

GridLevel grid_level(const ControlMesh& m, SubdivisionRule rule, int level) {
  namespace Far = OpenSubdiv::Far;
  GridLevel g{make_refiner(m, rule), {}, {}};
  Far::TopologyRefiner::UniformOptions options(level);
  options.fullTopologyInLastLevel = true;
  g.refiner->RefineUniform(options);
  std::vector<DoublePoint> all(g.refiner->GetNumVerticesTotal());
  for (size_t v = 0; v < m.positions.size(); ++v) all[v] = {{m.positions[v][0], m.positions[v][1], m.positions[v][2]}};
  DoublePoint* src = all.data();
  for (int l = 1; l <= level; ++l) {
    DoublePoint* dst = src + g.refiner->GetLevel(l - 1).GetNumVertices();
    Far::PrimvarRefinerReal<double>(*g.refiner).Interpolate(l, src, dst);
    src = dst;
  }
  for (int v = 0; v < g.refiner->GetLevel(level).GetNumVertices(); ++v) g.points.push_back({src[v].p[0], src[v].p[1], src[v].p[2]});
  g.corners = uniform_face_corner_coords(*g.refiner, rule, level);
  return g;
}

// Two edges between the same two vertices in Far's first levels: what the yardstick refuses.
bool folded(const ControlMesh& m, SubdivisionRule rule) {
  namespace Far = OpenSubdiv::Far;
  auto r = make_refiner(m, rule);
  Far::TopologyRefiner::UniformOptions options(2);
  options.fullTopologyInLastLevel = true;
  r->RefineUniform(options);
  for (int l = 0; l <= 2; ++l) {
    const Far::TopologyLevel& lv = r->GetLevel(l);
    for (int v = 0; v < lv.GetNumVertices(); ++v) {
      std::vector<int> ends;
      for (int e : lv.GetVertexEdges(v)) ends.push_back(lv.GetEdgeVertices(e)[0] + lv.GetEdgeVertices(e)[1] - v);
      std::sort(ends.begin(), ends.end());
      if (std::adjacent_find(ends.begin(), ends.end()) != ends.end()) return true;
    }
  }
  return false;
}

// The yardstick (Bfr where it is the limit, local refinement elsewhere) against an oracle built
// another way: Far's uniform refinement of the whole mesh to level 2, then each vertex's ring
// refined on (Far, in double) past the sharpness left at it plus six levels, where Far's masks
// (or the ring's eigenvectors at special vertices) give the limit. Every point of the level-2
// grid of every corpus shape, each face's side of it: positions to 1e-8 of the diagonal, normals
// to 0.001 degrees. Where the yardstick names no normal the oracle must have none either, or the
// face's normals just inside must point away from the oracle's (a face folded over: no one-sided
// limit); where the oracle has none (a ring folded flat) the count is printed.
TEST(LimitEvaluator, EqualsFarRefinedPastEverySharpnessOnEveryCorpusShape) {
  if (!corpus_present()) GTEST_SKIP() << "shared corpus not found beside the checkout";
  constexpr int kLevel = 2;
  long shapes = 0, samples = 0, no_normal = 0, oracle_blind = 0, folded_corners = 0;
  std::vector<std::string> refused;
  for (const auto& e : list_meshes()) {
    if (e.kind != "corpus" || e.name.rfind("opensubdiv/", 0) != 0) continue;
    const bool loop = e.name.find("/loop_") != std::string::npos;
    if (!loop && e.name.find("/catmark_") == std::string::npos) continue;
    const SubdivisionRule rule = loop ? SubdivisionRule::Loop : SubdivisionRule::CatmullClark;
    const ControlMesh loaded = load_mesh(e.name);
    // As loaded, and (Catmull-Clark with other faces than quads) as the quad schemes take it
    // (they take manifold meshes only).
    std::vector<ControlMesh> variants = {loaded};
    const MeshFacts facts = compute_facts(loaded);
    if (!loop && !facts.all_quads && facts.manifold()) variants.push_back(quadrangulate(loaded));
    for (const ControlMesh& m : variants) {
    const std::string name = e.name + (&m == &variants.front() ? "" : " (quadrangulated)");
    std::unique_ptr<LimitEvaluator> ref;
    try {
      ref = std::make_unique<LimitEvaluator>(m, rule);
    } catch (const Unsupported& u) {
      EXPECT_TRUE(folded(m, rule)) << name << " refused without folded faces: " << u.what();
      refused.push_back(name);
      continue;
    }
    EXPECT_FALSE(folded(m, rule)) << name << " has folded faces and was not refused";
    const GridLevel g = grid_level(m, rule, kLevel);
    const auto& level = g.refiner->GetLevel(kLevel);
    const double d = diag(m);
    std::map<int, VertexLimit> oracle;
    double worst_pos = 0, worst_deg = 0;
    for (int f = 0, i = 0; f < level.GetNumFaces(); ++f) {
      const auto fv = level.GetFaceVertices(f);
      for (int j = 0; j < fv.size(); ++j, ++i) {
        if (level.IsFaceHole(f) || !ref->has_limit(int(g.corners[i].face))) continue;
        const int v = fv[j];
        auto it = oracle.find(v);
        if (it == oracle.end())
          it = oracle.emplace(v, vertex_limit(level, g.refiner->GetSchemeOptions(), rule, g.points, v, 6)).first;
        const auto vf = level.GetVertexFaces(v);
        const int side = static_cast<int>(std::find(vf.begin(), vf.end(), f) - vf.begin());
        const LimitSample s = ref->evaluate(g.corners[i]);
        const Point3d& p = it->second.position;
        const double dp = std::sqrt(std::pow(s.position[0] - p[0], 2) + std::pow(s.position[1] - p[1], 2) +
                                    std::pow(s.position[2] - p[2], 2)) / d;
        worst_pos = std::max(worst_pos, dp);
        EXPECT_LE(dp, 1e-8) << name << " ptex " << g.corners[i].face << " (" << g.corners[i].u << ", " << g.corners[i].v << ")";
        const Point3d& n = it->second.normal[side];
        const bool ours = s.normal[0] * s.normal[0] + s.normal[1] * s.normal[1] + s.normal[2] * s.normal[2] > 0.25;
        const bool theirs = n[0] * n[0] + n[1] * n[1] + n[2] * n[2] > 0.25;
        ++samples;
        no_normal += !ours;
        if (!theirs) {
          ++oracle_blind;
          continue;
        }
        if (!ours) {
          // Only where the normals inside the face lead the other way (a face folded over its
          // neighbour): the corner has no one-sided normal, whatever the ring's eigenvectors say.
          const SurfaceCoord c = g.corners[i];
          const float mid = loop ? 1.0f / 3 : 0.5f;
          const LimitSample in = ref->evaluate({c.face, c.u + 1e-3f * (mid - c.u), c.v + 1e-3f * (mid - c.v)});
          EXPECT_LT(in.normal[0] * n[0] + in.normal[1] * n[1] + in.normal[2] * n[2], 0)
              << name << ": no normal where the oracle has one, ptex " << c.face << " (" << c.u << ", " << c.v << ")";
          ++folded_corners;
          continue;
        }
        const Point3d c = {s.normal[1] * n[2] - s.normal[2] * n[1], s.normal[2] * n[0] - s.normal[0] * n[2],
                           s.normal[0] * n[1] - s.normal[1] * n[0]};
        const double deg = std::atan2(std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]),
                                      s.normal[0] * n[0] + s.normal[1] * n[1] + s.normal[2] * n[2]) * 180 / M_PI;
        worst_deg = std::max(worst_deg, deg);
        EXPECT_LE(deg, 1e-3) << name << " ptex " << g.corners[i].face << " (" << g.corners[i].u << ", "
                             << g.corners[i].v << ")";
      }
    }
    ++shapes;
    std::printf("  %-52s positions %.1e, normals %.1e deg\n", name.c_str(), worst_pos, worst_deg);
    }
  }
  std::string names;
  for (const auto& n : refused) names += " " + n;
  std::printf("%ld shapes, %ld points (sides) of the level-%d grid: %ld with no normal in the yardstick (%ld corners "
              "whose face folds over), %ld where the oracle has none (not compared); refused (folded faces):%s\n",
              shapes, samples, kLevel, no_normal, folded_corners, oracle_blind, names.c_str());
  EXPECT_GE(shapes, 120);
}

TEST(BfrDefect, ManifoldBuiltinsHaveNone) {
  for (const char* name : {"torus", "quadsphere", "pole3", "creased-cube", "open-patch", "icosphere", "frog-standin"})
    EXPECT_FALSE(bfr_overlapping_patch_defect(load_mesh(name))) << name;
}
