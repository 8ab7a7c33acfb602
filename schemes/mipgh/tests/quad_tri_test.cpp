// mipgh-quadtri against three oracles:
//   - on quads only it is mipgh-cc's refinement, on triangles only mipgh-loop's, bit for bit, on
//     the built-ins and every all-quad or all-triangle shape of the corpus sweep (creases,
//     corners, boundaries; both of those equal OpenSubdiv, mipgh_test);
//   - where quads and triangles meet, one step equals Stam and Loop's rule written out directly on
//     the face list (linear split, then every node moved by its new faces' weighted points), an
//     implementation that shares nothing with the D-atlas;
//   - the mixed meshes the issue names come out watertight (the input's boundary open, no ray
//     crack), and the R1 split takes their pentagons.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "datasets/generators.h"
#include "datasets/manifest.h"
#include "harness/conformance/sweep_corpus.h"
#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/mesh/acceptance.h"
#include "harness/mesh/facts.h"
#include "harness/validate/watertight.h"
#include "schemes/mipgh/atlas.h"
#include "schemes/mipgh/lod.h"
#include "schemes/mipgh/mipgh.h"

using namespace sdb;
using namespace sdb::mipgh;

namespace {

Tessellation run(const ControlMesh& m, MeshRule rule, int depth, Backend backend = Backend::Cpu) {
  const char* name = rule == MeshRule::QuadTri ? "mipgh-quadtri" : rule == MeshRule::Loop ? "mipgh-loop" : "mipgh-cc";
  auto e = make_evaluation(m, rule, default_request(find_scheme(name)->info(), backend, depth), false);
  e->execute();
  return e->result();
}

// The cube with one face cut into two triangles: closed, two quads and two triangles meeting at
// the cut's ends, mixed edges around it.
ControlMesh cut_cube() {
  ControlMesh m = gen::cube();
  const std::vector<int> first(m.face_vertices.begin(), m.face_vertices.begin() + 4);
  m.face_sizes.erase(m.face_sizes.begin());
  m.face_vertices.erase(m.face_vertices.begin(), m.face_vertices.begin() + 4);
  m.face_sizes.insert(m.face_sizes.end(), {3, 3});
  m.face_vertices.insert(m.face_vertices.end(), {first[0], first[1], first[2], first[0], first[2], first[3]});
  m.name = "cut-cube";
  return m;
}

// Stam and Loop's step written out on the face list of a closed quad/triangle mesh: the linear
// split's nodes (vertices, edge midpoints, quad centroids), each moved to x + a (c - x).
struct DirectStep {
  std::vector<std::array<double, 3>> node;  // vertices, then edges (edge_index), then quads (quad_index)
  std::map<std::pair<int, int>, int> edge_index;
  std::vector<int> quad_index;               // per face, -1 for a triangle
};

DirectStep direct_step(const ControlMesh& m) {
  using P = std::array<double, 3>;
  DirectStep s;
  for (const Point3& p : m.positions) s.node.push_back({p[0], p[1], p[2]});
  const std::vector<int> off = face_offsets(m);
  auto mid = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    auto [it, fresh] = s.edge_index.emplace(key, int(s.node.size()));
    if (fresh) {
      const P &p = s.node[a], &q = s.node[b];
      s.node.push_back({(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2});
    }
    return it->second;
  };
  std::vector<std::vector<int>> faces;  // the linear split's faces
  for (int f = 0; f < num_faces(m); ++f) {
    const int n = m.face_sizes[f], *v = m.face_vertices.data() + off[f];
    std::vector<int> mids;
    for (int i = 0; i < n; ++i) mids.push_back(mid(v[i], v[(i + 1) % n]));
    if (n == 3) {
      for (int i = 0; i < 3; ++i) faces.push_back({v[i], mids[i], mids[(i + 2) % 3]});
      faces.push_back({mids[0], mids[1], mids[2]});
      s.quad_index.push_back(-1);
      continue;
    }
    P c{0, 0, 0};
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) c[k] += s.node[v[i]][k] / 4;
    const int centre = int(s.node.size());
    s.node.push_back(c);
    s.quad_index.push_back(centre);
    for (int i = 0; i < 4; ++i) faces.push_back({v[i], mids[i], centre, mids[(i + 3) % 4]});
  }
  // c = sum of angle * point over the node's faces / sum of angles (a quad pi/2, a triangle pi/3)
  std::vector<P> sum(s.node.size(), P{0, 0, 0});
  std::vector<double> angles(s.node.size(), 0);
  std::vector<int> quads(s.node.size(), 0), triangles(s.node.size(), 0);
  for (const auto& f : faces)
    for (size_t i = 0; i < f.size(); ++i) {
      const int x = f[i];
      P p{0, 0, 0};
      for (size_t j = 0; j < f.size(); ++j) {
        const double w = f.size() == 4 ? 0.25 : (j == i ? 0.25 : 0.375);
        for (int k = 0; k < 3; ++k) p[k] += w * s.node[f[j]][k];
      }
      const double angle = f.size() == 4 ? M_PI / 2 : M_PI / 3;
      for (int k = 0; k < 3; ++k) sum[x][k] += angle * p[k];
      angles[x] += angle, ++(f.size() == 4 ? quads : triangles)[x];
    }
  for (size_t x = 0; x < s.node.size(); ++x) {
    const int n = quads[x] + triangles[x];
    const double a = triangles[x] == 0 ? 4.0 / n
                     : quads[x] == 0   ? 5.0 / 3 - 8.0 / 3 * std::pow(0.375 + 0.25 * std::cos(2 * M_PI / n), 2)
                                       : 12.0 / (3 * quads[x] + 2 * triangles[x]);
    for (int k = 0; k < 3; ++k) s.node[x][k] += a * (sum[x][k] / angles[x] - s.node[x][k]);
  }
  return s;
}

// Largest distance over the diagonal between mipgh-quadtri's depth-1 nodes and the direct step.
double against_direct_step(const ControlMesh& m) {
  const Tessellation t = run(m, MeshRule::QuadTri, 1);
  const DirectStep s = direct_step(m);
  const DAtlas atlas = build_atlas(m, FacetKinds::QuadsAndTriangles);
  const LevelLayout l = level_layout(atlas, 1);
  const double d = bounds_of(m.positions).diagonal();
  double worst = 0;
  auto compare = [&](uint32_t node, int direct) {
    const Point3& p = t.positions[node];
    const auto& q = s.node[direct];
    worst = std::max(worst, std::sqrt(std::pow(p[0] - q[0], 2) + std::pow(p[1] - q[1], 2) + std::pow(p[2] - q[2], 2)) / d);
  };
  for (int v = 0; v < atlas.num_vertices; ++v) compare(uint32_t(v), v);
  for (int e = 0; e < atlas.num_edges(); ++e) {
    const HalfEdge h = atlas.edges[e].major;
    const int a = atlas.facet_corners[h.facet][h.side], b = atlas.facet_corners[h.facet][atlas.next(h.facet, h.side)];
    compare(l.edge_node(e, 0), s.edge_index.at(std::minmax(a, b)));
  }
  for (int f = 0; f < atlas.num_facets(); ++f)
    if (atlas.facet_size[f] == 4) compare(l.interior(f), s.quad_index[f]);
  return worst;
}

TEST(MipghQuadTri, MixedStepEqualsStamAndLoopWrittenOut) {
  const double cut = against_direct_step(cut_cube());
  std::printf("  cut-cube: %.2g of the diagonal\n", cut);
  EXPECT_LE(cut, 1e-6);
  const SchemeInfo& info = find_scheme("mipgh-quadtri")->info();
  for (const char* name : {"crane/spot_control", "crane/blub_control"}) {
    ControlMesh m;
    try {
      m = accept_mesh(load_mesh(name), info);
    } catch (const InputError&) {
      continue;  // no shared corpus here
    }
    const MeshFacts facts = compute_facts(m);
    ASSERT_TRUE(facts.closed) << name;
    ASSERT_TRUE(facts.face_sizes.count(3) && facts.face_sizes.count(4)) << name << ": the pentagons split into quads and triangles";
    const double worst = against_direct_step(m);
    std::printf("  %s: %.2g of the diagonal\n", name, worst);
    EXPECT_LE(worst, 1e-6) << name;
  }
}

// Every node, every depth: quads only gives mipgh-cc's nodes, triangles only mipgh-loop's.
void expect_pure(const ControlMesh& m, MeshRule pure, const std::string& name, int max_depth, long& runs) {
  const long per_face = pure == MeshRule::Loop ? 1 : 2;
  for (int depth = 1; depth <= max_depth; ++depth) {
    if (depth > 1 && (long(num_faces(m)) * per_face << (2 * depth)) > 100000) break;
    const Tessellation q = run(m, MeshRule::QuadTri, depth), r = run(m, pure, depth);
    ASSERT_EQ(q.triangles, r.triangles) << name;
    EXPECT_TRUE(q.positions == r.positions) << name << " depth " << depth;
    ++runs;
  }
}

TEST(MipghQuadTri, QuadsOnlyIsCatmullClarkAndTrianglesOnlyIsLoop) {
  long runs = 0;
  for (const ControlMesh& m : {gen::torus(8, 6), gen::cube(), gen::creased_cube(), gen::pole(8), gen::open_patch(3, 4)})
    expect_pure(m, MeshRule::CatmullClark, m.name, 4, runs);
  for (const ControlMesh& m : {gen::icosphere(1), gen::tetrahedron()}) expect_pure(m, MeshRule::Loop, m.name, 4, runs);
  int shapes = 0;
  for (SubdivisionRule rule : {SubdivisionRule::CatmullClark, SubdivisionRule::Loop})
    for (const std::string& name : conformance::sweep_shapes(rule)) {
      ControlMesh m;
      try {
        m = conformance::sweep_mesh(name, rule, "mipgh-quadtri");
        build_atlas(m, FacetKinds::QuadsAndTriangles);
      } catch (const InputError&) {
        continue;  // non-manifold: refused by every mipgh scheme
      }
      const MeshFacts f = compute_facts(m);
      const bool quads = rule == SubdivisionRule::CatmullClark && f.all_quads, triangles = rule == SubdivisionRule::Loop && f.all_triangles;
      if (!quads && !triangles) continue;
      expect_pure(m, quads ? MeshRule::CatmullClark : MeshRule::Loop, name, 3, runs);
      ++shapes;
    }
  std::printf("  %ld runs equal bit for bit (%d corpus shapes)\n", runs, shapes);
}

TEST(MipghQuadTri, MixedMeshesAreWatertight) {
  const SchemeInfo& info = find_scheme("mipgh-quadtri")->info();
  std::vector<ControlMesh> meshes = {cut_cube()};
  for (const char* name : {"pmp/suzanne", "stein/sword_quad_dominant", "crane/spot_control", "crane/blub_control"}) {
    try {
      meshes.push_back(accept_mesh(load_mesh(name), info));
    } catch (const InputError&) {
    }
  }
  for (const ControlMesh& m : meshes) {
    const bool closed = compute_facts(m).closed && m.holes.empty();
    for (int depth = 1; depth <= 3; ++depth) {
      if (depth > 1 && (long(num_faces(m)) * 2 << (2 * depth)) > 400000) break;
      const Tessellation t = run(m, MeshRule::QuadTri, depth), mt = run(m, MeshRule::QuadTri, depth, Backend::CpuMt);
      EXPECT_TRUE(t.positions == mt.positions) << m.name << ": cpu-mt differs from cpu";
      EXPECT_EQ(count_open_edges(t), conformance::boundary_edges(m) << depth) << m.name << " depth " << depth;
      long cracks = -1;
      if (closed) {
        const RayCrackReport c = ray_crack_check(t, {50000, 50000, 1});
        EXPECT_EQ(c.cracks, 0) << m.name << " depth " << depth;
        cracks = c.cracks;
      }
      std::printf("  %-28s depth %d: %zu triangles, %ld open edges, %ld cracks\n", m.name.c_str(), depth,
                  t.triangles.size() / 3, count_open_edges(t), cracks);
    }
  }
}

TEST(MipghQuadTri, RefusesTheLimit) {
  const SchemeInfo& info = find_scheme("mipgh-quadtri")->info();
  EXPECT_THROW(make_evaluation(cut_cube(), MeshRule::QuadTri, default_request(info, Backend::Cpu, 2), true), Unsupported);
}

}  // namespace
