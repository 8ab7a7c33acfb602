// Adaptive refinement (Figures 13, 14) against uniform refinement, on the corpus sweep, with three
// criteria per mesh:
//   - every node of a D-facet refined to level d equals uniform refinement's node at depth d bit
//     for bit (the auxiliary layer gives its 1-disks exactly what uniform refinement does);
//   - the output, each D-facet drawn at its label: every node within 1e-6 of the diagonal of the
//     uniform output's limit at the same surface point; open edges exactly the boundary at the
//     level each boundary D-edge is drawn; on closed inputs no ray crack in 100,000 lines;
//   - cpu-mt equals cpu bit for bit; adaptive draws fewer triangles than uniform.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <tuple>

#include "harness/conformance/far_oracle.h"
#include "harness/conformance/sweep_corpus.h"
#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/mesh/facts.h"
#include "harness/validate/watertight.h"
#include "schemes/mipgh/mipgh.h"
#include "schemes/mipgh/mutation.h"
#include "schemes/mipgh/primitives.h"

using namespace sdb;
using namespace sdb::mipgh;

namespace {

constexpr int kDepth = 3;
const AdaptiveCriterion kCriteria[] = {{Refinement::Region, 0.5}, {Refinement::Curvature, 0.5}, {Refinement::Camera, 0.5}};

const char* scheme_name(SubdivisionRule rule) { return rule == SubdivisionRule::Loop ? "mipgh-loop" : "mipgh-cc"; }
FacetKinds kinds(SubdivisionRule rule) { return rule == SubdivisionRule::Loop ? FacetKinds::Triangles : FacetKinds::Quads; }

// Every level's nodes, refined as the cpu backend refines them (relative to the box's centre).
std::vector<std::vector<V3>> levels_of(const MeshMutation& m, const ControlMesh& mesh) {
  std::vector<std::vector<V3>> levels(1, std::vector<V3>(m.lod.layout(0).num_nodes));
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const Point3& p = mesh.positions[v];
    levels[0][v] = {p[0] - m.origin[0], p[1] - m.origin[1], p[2] - m.origin[2]};
  }
  for (int sigma = 0; sigma < m.inner_depth(); ++sigma) {
    levels.emplace_back(m.lod.layout(sigma + 1).num_nodes);
    m.processor.step(sigma, levels[sigma].data(), levels[sigma + 1].data(), false);
  }
  return levels;
}

// A mutation and every level it refines, built once per shape (uniform) or criterion (adaptive)
// for all the comparisons that read them.
struct Refined {
  std::unique_ptr<const MeshMutation> mutation;
  std::vector<std::vector<V3>> levels;
};
Refined refine(const ControlMesh& mesh, SubdivisionRule rule, bool limit, AdaptiveCriterion c = {}) {
  auto m = std::make_unique<const MeshMutation>(mesh, mesh_rule(rule), build_atlas(mesh, kinds(rule)), kDepth, limit, c);
  std::vector<std::vector<V3>> levels = levels_of(*m, mesh);
  return {std::move(m), std::move(levels)};
}

// Nodes of refined D-facets that differ from uniform refinement's, and how many were compared.
std::pair<long, long> refined_against_uniform(const Refined& uniform, const Refined& adaptive) {
  const MeshMutation &um = *uniform.mutation, &am = *adaptive.mutation;
  const auto &u = uniform.levels, &a = adaptive.levels;
  long differ = 0, compared = 0;
  for (int sigma = 0; sigma <= am.inner_depth(); ++sigma) {
    const int n = am.lod.layout(sigma).n;
    for (int f = 0; f < am.atlas.num_facets(); ++f) {
      if (am.lod.label(f) < sigma) continue;
      const int size = am.atlas.facet_size[f], count = size == 4 ? n * n : n * (n + 1) / 2;
      const uint32_t *ia = am.lod.facet(sigma, f), *iu = um.lod.facet(sigma, f);
      for (int o = 0; o < count; ++o, ++compared)
        differ += std::memcmp(&a[sigma][ia[o]], &u[sigma][iu[o]], sizeof(V3)) != 0;
    }
  }
  return {differ, compared};
}

// Open micro-edges expected: every D-edge with one drawn D-facet, at the finer of its D-facets' levels.
long expected_open_edges(const MeshMutation& m) {
  long open = 0;
  for (const DEdge& e : m.atlas.edges) {
    const bool major = !m.atlas.facet_hole[e.major.facet], minor = !e.minor.null() && !m.atlas.facet_hole[e.minor.facet];
    if (major == minor) continue;
    const int level = std::max<int>(m.render[e.major.facet], e.minor.null() ? 0 : m.render[e.minor.facet]);
    open += 1L << level;
  }
  return open;
}

using CoordKey = std::tuple<uint32_t, float, float>;

Tessellation evaluate(const ControlMesh& mesh, SubdivisionRule rule, Backend backend, AdaptiveCriterion c = {},
                      int depth = kDepth) {
  const SchemeInfo& info = find_scheme(scheme_name(rule))->info();
  auto e = make_evaluation(mesh, rule, default_request(info, backend, depth), true, c);
  e->execute();
  return e->result();
}

void sweep(SubdivisionRule rule) {
  const std::vector<std::string> shapes = conformance::sweep_shapes(rule);
  if (shapes.empty()) GTEST_SKIP() << "no shared corpus";
  long differ = 0, compared = 0, mismatches = 0, rays = 0, cracks = 0, settings = 0;
  double worst = 0;
  for (const std::string& name : shapes) {
    ControlMesh mesh;
    try {
      mesh = conformance::sweep_mesh(name, rule, scheme_name(rule));
      build_atlas(mesh, kinds(rule));
    } catch (const InputError&) {
      continue;  // refused as the uniform sweep refuses it
    }
    const double diagonal = bounds_of(mesh.positions).diagonal();
    const bool closed = compute_facts(mesh).closed && mesh.holes.empty();
    // Uniform output at every depth, by surface point: the output node drawn at level l comes from
    // level home[l], as uniform refinement's at the deepest depth with that home.
    const DAtlas atlas = build_atlas(mesh, kinds(rule));
    std::vector<std::map<CoordKey, size_t>> at(kDepth + 1);
    std::vector<Tessellation> uniform(kDepth + 1);
    for (int l = 0; l <= kDepth; ++l) {
      uniform[l] = evaluate(mesh, rule, Backend::Cpu, {}, l);
      for (size_t i = 0; i < uniform[l].coords.size(); ++i)
        if (i >= mesh.positions.size() || atlas.valence(int(i)) > 0)  // a bare vertex stands at no surface point
          at[l][{uniform[l].coords[i].face, uniform[l].coords[i].u, uniform[l].coords[i].v}] = i;
    }
    // Uniform refinement's levels, without and with the limit's deeper levels: one each for the
    // three criteria (they were refined again for every criterion).
    const Refined uniform_levels[2] = {refine(mesh, rule, false), refine(mesh, rule, true)};
    for (const AdaptiveCriterion& c : kCriteria) {
      Refined adaptive_limit;  // the mutation the output below is checked against too
      for (bool limit : {false, true}) {
        Refined adaptive = refine(mesh, rule, limit, c);
        const auto [d, n] = refined_against_uniform(uniform_levels[limit], adaptive);
        EXPECT_EQ(d, 0) << name << " criterion " << int(c.kind) << " limit " << limit;
        differ += d, compared += n;
        if (limit) adaptive_limit = std::move(adaptive);
      }
      const Tessellation t = evaluate(mesh, rule, Backend::Cpu, c);
      const MeshMutation& m = *adaptive_limit.mutation;
      EXPECT_EQ(count_open_edges(t), expected_open_edges(m)) << name << " criterion " << int(c.kind);
      Tessellation scratch;
      const AdaptiveOutput homes = compile_adaptive(m.atlas, m.lod, m.render, m.home, scratch);
      std::vector<int> home_of(t.positions.size(), -1);
      for (size_t h = 0; h < homes.nodes.size(); ++h)
        for (const auto& [node, i] : homes.nodes[h]) home_of[i] = int(h);
      long mismatched = 0;
      for (size_t i = 0; i < t.coords.size(); ++i) {
        if (i < mesh.positions.size() && atlas.valence(int(i)) == 0) continue;  // a bare vertex
        int l = kDepth;
        while (m.home[l] != home_of[i]) --l;
        const auto it = at[l].find({t.coords[i].face, t.coords[i].u, t.coords[i].v});
        ASSERT_NE(it, at[l].end()) << name << " node " << i;
        const size_t j = it->second;
        mismatched += t.positions[i] != uniform[l].positions[j] || t.normals[i] != uniform[l].normals[j];
        worst = std::max(worst, conformance::distance(t.positions[i], uniform[kDepth].positions[
                                    at[kDepth].at({t.coords[i].face, t.coords[i].u, t.coords[i].v})]) / diagonal);
      }
      EXPECT_EQ(mismatched, 0) << name << " criterion " << int(c.kind);
      mismatches += mismatched;
      if (closed) {
        const RayCrackReport r = ray_crack_check(t, {100000, 10000, 1});
        EXPECT_EQ(r.cracks, 0) << name << " criterion " << int(c.kind);
        rays += r.rays, cracks += r.cracks;
      }
      ++settings;
    }
  }
  std::printf("%s adaptive, depth %d: %ld settings; %ld refined nodes against uniform, %ld differ; output nodes "
              "unlike uniform's from the same level: %ld (from uniform's at depth %d: at most %.2g of the diagonal); "
              "%ld rays, %ld cracks\n",
              scheme_name(rule), kDepth, settings, compared, differ, mismatches, kDepth, worst, rays, cracks);
}

}  // namespace

TEST(MipghAdaptiveSweep, CatmullClarkCorpusEqualsUniformAndIsWatertight) { sweep(SubdivisionRule::CatmullClark); }
TEST(MipghAdaptiveSweep, LoopCorpusEqualsUniformAndIsWatertight) { sweep(SubdivisionRule::Loop); }

TEST(MipghAdaptive, CpuMtEqualsCpuAndDrawsFewerTriangles) {
  const ControlMesh mesh = conformance::sweep_mesh("frog-standin", SubdivisionRule::CatmullClark, "mipgh-cc");
  const Tessellation uniform = evaluate(mesh, SubdivisionRule::CatmullClark, Backend::Cpu);
  for (const AdaptiveCriterion& c : kCriteria) {
    const Tessellation a = evaluate(mesh, SubdivisionRule::CatmullClark, Backend::Cpu, c);
    const Tessellation b = evaluate(mesh, SubdivisionRule::CatmullClark, Backend::CpuMt, c);
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.normals, b.normals);
    EXPECT_LT(a.triangles.size(), uniform.triangles.size()) << int(c.kind);
  }
}

TEST(MipghAdaptive, CriteriaLabelTheDFacetsTheySay) {
  const ControlMesh mesh = conformance::sweep_mesh("frog-standin", SubdivisionRule::CatmullClark, "mipgh-cc");
  const DAtlas atlas = build_atlas(mesh, FacetKinds::Quads);
  for (const AdaptiveCriterion& c : kCriteria) {
    const std::vector<uint8_t> l = facet_labels(atlas, mesh.positions, c, 4);
    // each criterion refines some D-facets fully and leaves others coarser
    EXPECT_EQ(*std::max_element(l.begin(), l.end()), 4) << int(c.kind);
    EXPECT_LT(*std::min_element(l.begin(), l.end()), 4) << int(c.kind);
  }
  // a region taking the whole box is uniform refinement
  const std::vector<uint8_t> all = facet_labels(atlas, mesh.positions, {Refinement::Region, 1.0}, 4);
  EXPECT_EQ(*std::min_element(all.begin(), all.end()), 4);
}
