#include "schemes/halfedge/topology.h"

#include <opensubdiv/sdc/crease.h>
#include <opensubdiv/sdc/options.h>

#include <algorithm>
#include <map>
#include <unordered_map>

#include "harness/core/errors.h"

namespace sdb::halfedge {
namespace {

namespace Sdc = OpenSubdiv::Sdc;
using refined::kInfiniteSharpness;

uint64_t edge_key(uint32_t a, uint32_t b) { return uint64_t(a) << 32 | b; }

Sdc::Options sdc_options(const ControlMesh& m) {
  Sdc::Options o;
  o.SetCreasingMethod(m.crease_method == CreaseMethod::Chaikin ? Sdc::Options::CREASE_CHAIKIN
                                                                 : Sdc::Options::CREASE_UNIFORM);
  return o;
}

// Base-level sharpness as Far's factory sets it: the mesh's creases and corners, boundary edges
// infinitely sharp, and under "edge and corner" a vertex of one face and two edges a corner.
void base_sharpness(const ControlMesh& m, Level& l, const std::unordered_map<uint64_t, uint32_t>& corner_of) {
  std::vector<float> es(l.num_edges, 0.0f), vs(l.num_vertices, 0.0f);
  bool any = false;
  for (const EdgeCrease& c : m.creases) {
    auto it = corner_of.find(edge_key(c.v0, c.v1));
    if (it == corner_of.end()) it = corner_of.find(edge_key(c.v1, c.v0));
    if (it == corner_of.end()) continue;  // not an edge: Far skips it too
    es[l.edge[it->second]] = std::max(0.0f, c.sharpness);
    any = any || c.sharpness > 0;
  }
  for (const VertexCorner& c : m.corners)
    if (c.vertex >= 0 && c.vertex < int(l.num_vertices)) vs[c.vertex] = std::max(0.0f, c.sharpness), any = any || c.sharpness > 0;
  std::vector<int> faces(l.num_vertices, 0), edges(l.num_vertices, 0);
  for (uint64_t h = 0; h < l.num_halfedges; ++h) {
    ++faces[l.vert[h]];
    if (l.twin[h] == kNone) {
      es[l.edge[h]] = kInfiniteSharpness, any = true;
      ++edges[l.vert[l.next(uint32_t(h))]];  // the boundary edge's far end meets one more edge than faces
    }
  }
  if (m.boundary == BoundaryRule::EdgeAndCorner)
    for (uint32_t v = 0; v < l.num_vertices; ++v)
      if (faces[v] == 1 && edges[v] == 1) vs[v] = kInfiniteSharpness, any = true;
  if (!any) return;
  l.edge_sharpness = std::move(es);
  l.vertex_sharpness = std::move(vs);
}

// A vertex whose faces form more than one fan (two cones meeting at a point) has no single ring:
// a walk around it misses faces. OpenSubdiv makes it a corner; a halfedge has one twin.
void check_manifold_vertices(const ControlMesh& m, const Level& l) {
  std::vector<uint32_t> corners(l.num_vertices, 0);
  for (uint32_t v : l.vert) ++corners[v];
  for (uint32_t v = 0; v < l.num_vertices; ++v) {
    const uint32_t start = l.vertex_corner[v];
    if (start == kNone) continue;
    uint32_t k = start, walked = 0;
    while (true) {
      ++walked;
      const uint32_t t = l.twin[l.prev(k)];
      if (t == kNone || (k = t) == start || walked > corners[v]) break;
    }
    if (walked != corners[v])
      throw InputError(m.source, "vertex " + std::to_string(v + 1) + " is not manifold: its " + std::to_string(corners[v]) +
                                     " faces form more than one fan, which the halfedge rules' rings do not take");
  }
}

void index_edges_and_vertices(Level& l) {
  l.edge_corner.assign(l.num_edges, kNone);
  for (uint64_t h = 0; h < l.num_halfedges; ++h)
    if (l.edge_corner[l.edge[h]] == kNone) l.edge_corner[l.edge[h]] = uint32_t(h);
  l.vertex_corner = refined::vertex_corners(l.face_level());
}

// The child sharpness of the halves of every edge and of every vertex (Sdc::Crease's rules).
void refine_sharpness(const ControlMesh& m, const Level& p, Level& c) {
  if (p.edge_sharpness.empty()) return;
  const Sdc::Crease crease(sdc_options(m));
  c.edge_sharpness.assign(c.num_edges, 0.0f);
  c.vertex_sharpness.assign(c.num_vertices, 0.0f);
  std::vector<float> around;
  for (uint32_t e = 0; e < p.num_edges; ++e) {
    const float s = p.edge_sharpness[e];
    if (s <= 0.0f) continue;
    const uint32_t h = p.edge_corner[e], t = p.twin[h];
    // Half 2e + j lies at the vertex of the larger halfedge for j = 0 (a boundary edge's only
    // one), at the other for j = 1 (the rule's edge numbering, topology.h).
    const uint32_t ends[2] = {p.vert[t == kNone || h > t ? h : t], p.vert[t == kNone || h > t ? p.next(h) : h]};
    for (int j = 0; j < 2; ++j) {
      float child = 0.0f;
      if (crease.IsUniform() || s >= kInfiniteSharpness) {
        child = crease.SubdivideUniformSharpness(s);
      } else {
        around.clear();
        const uint32_t v = ends[j], start = p.vertex_corner[v];
        uint32_t k = start;
        while (true) {
          around.push_back(p.sharpness_of_edge(p.edge[k]));
          const uint32_t q = p.prev(k), tw = p.twin[q];
          if (tw == kNone) {
            around.push_back(p.sharpness_of_edge(p.edge[q]));
            break;
          }
          if ((k = tw) == start) break;
        }
        child = crease.SubdivideEdgeSharpnessAtVertex(s, int(around.size()), around.data());
      }
      c.edge_sharpness[2 * e + j] = child;
    }
  }
  for (uint32_t v = 0; v < p.num_vertices; ++v) c.vertex_sharpness[v] = crease.SubdivideVertexSharpness(p.sharpness_of_vertex(v));
}

Level refine_catmark(const Level& p) {
  Level c;
  c.face_size = 4;
  c.num_halfedges = 4 * p.num_halfedges;
  c.num_faces = uint32_t(p.num_halfedges);
  c.num_edges = 2 * p.num_edges + uint32_t(p.num_halfedges);
  c.num_vertices = p.num_vertices + p.num_faces + p.num_edges;
  c.twin.resize(c.num_halfedges), c.vert.resize(c.num_halfedges), c.edge.resize(c.num_halfedges);
  const uint32_t V = p.num_vertices, F = p.num_faces, E = p.num_edges;
  for (uint32_t h = 0; h < p.num_halfedges; ++h) {
    const uint32_t twin = p.twin[h], next = p.next(h), prev = p.prev(h), prev_twin = p.twin[prev];
    const uint32_t e = p.edge[h], prev_e = p.edge[prev];
    uint32_t* t = &c.twin[4 * uint64_t(h)];
    t[0] = twin == kNone ? kNone : 4 * p.next(twin) + 3;
    t[1] = 4 * next + 2;
    t[2] = 4 * prev + 1;
    t[3] = prev_twin == kNone ? kNone : 4 * prev_twin + 0;
    uint32_t* v = &c.vert[4 * uint64_t(h)];
    v[0] = p.vert[h], v[1] = V + F + e, v[2] = V + p.face(h), v[3] = V + F + prev_e;
    uint32_t* k = &c.edge[4 * uint64_t(h)];
    k[0] = 2 * e + (twin == kNone || h > twin ? 0 : 1);
    k[1] = 2 * E + h;
    k[2] = 2 * E + prev;
    k[3] = 2 * prev_e + (prev_twin == kNone || prev > prev_twin ? 1 : 0);
  }
  return c;
}

Level refine_loop(const Level& p) {
  Level c;
  c.face_size = 3;
  const uint32_t H = uint32_t(p.num_halfedges);
  c.num_halfedges = 4 * p.num_halfedges;
  c.num_faces = 4 * p.num_faces;
  c.num_edges = 2 * p.num_edges + H;
  c.num_vertices = p.num_vertices + p.num_edges;
  c.twin.resize(c.num_halfedges), c.vert.resize(c.num_halfedges), c.edge.resize(c.num_halfedges);
  const uint32_t V = p.num_vertices, E = p.num_edges;
  for (uint32_t h = 0; h < H; ++h) {
    const uint32_t twin = p.twin[h], prev = p.prev(h), prev_twin = p.twin[prev];
    const uint32_t e = p.edge[h], prev_e = p.edge[prev];
    // The corner triangle at vert(h): 3h, 3h + 1, 3h + 2; the middle triangle's side: 3H + h.
    c.twin[3 * h + 0] = twin == kNone ? kNone : 3 * p.next(twin) + 2;
    c.twin[3 * h + 1] = 3 * H + h;
    c.twin[3 * h + 2] = prev_twin == kNone ? kNone : 3 * prev_twin + 0;
    c.twin[3 * H + h] = 3 * h + 1;
    c.vert[3 * h + 0] = p.vert[h];
    c.vert[3 * h + 1] = V + e;
    c.vert[3 * h + 2] = V + prev_e;
    c.vert[3 * H + h] = V + prev_e;
    c.edge[3 * h + 0] = 2 * e + (twin == kNone || h > twin ? 0 : 1);
    c.edge[3 * h + 1] = 2 * E + h;
    c.edge[3 * h + 2] = 2 * prev_e + (prev_twin == kNone || prev > prev_twin ? 1 : 0);
    c.edge[3 * H + h] = 2 * E + h;
  }
  return c;
}

}  // namespace

refined::FaceLevel Level::face_level() const {
  refined::FaceLevel f;
  f.face_size = face_size;
  f.num_vertices = num_vertices;
  f.verts = vert.data();
  f.twin = twin.data();
  f.num_corners = num_halfedges;
  if (!edge_sharpness.empty()) f.edge_sharpness = [this](uint32_t h) { return edge_sharpness[edge[h]]; };
  if (!vertex_sharpness.empty()) f.vertex_sharpness = [this](uint32_t v) { return vertex_sharpness[v]; };
  return f;
}

namespace {

// The mesh without the vertices no face uses, and which mesh vertex each remaining one is.
ControlMesh without_bare_vertices(const ControlMesh& m, std::vector<uint32_t>& kept) {
  std::vector<uint32_t> index(m.positions.size(), kNone);
  for (int v : m.face_vertices) index[v] = 0;
  kept.clear();
  for (size_t v = 0; v < index.size(); ++v)
    if (index[v] == 0) index[v] = uint32_t(kept.size()), kept.push_back(uint32_t(v));
  if (kept.size() == m.positions.size()) {
    kept.clear();
    return m;
  }
  ControlMesh out = m;
  out.positions.clear();
  for (uint32_t v : kept) out.positions.push_back(m.positions[v]);
  for (int& v : out.face_vertices) v = int(index[v]);
  out.creases.clear(), out.corners.clear();
  for (const EdgeCrease& c : m.creases)
    if (index[c.v0] != kNone && index[c.v1] != kNone) out.creases.push_back({int(index[c.v0]), int(index[c.v1]), c.sharpness});
  for (const VertexCorner& c : m.corners)
    if (c.vertex >= 0 && size_t(c.vertex) < index.size() && index[c.vertex] != kNone)
      out.corners.push_back({int(index[c.vertex]), c.sharpness});
  return out;
}

}  // namespace

Level base_level(const ControlMesh& mesh, SubdivisionRule rule, std::vector<uint32_t>* base_vertices) {
  std::vector<uint32_t> kept;
  const ControlMesh m = without_bare_vertices(mesh, kept);
  if (base_vertices) *base_vertices = kept;
  if (rule == SubdivisionRule::CatmullClark && m.triangle_rule == TriangleRule::Smooth &&
      std::find(m.face_sizes.begin(), m.face_sizes.end(), 3) != m.face_sizes.end())
    throw InputError(m.source, "Catmull-Clark's \"smooth triangle\" rule is not the halfedge rules' (they weigh triangles as any face)");
  Level l;
  l.num_vertices = num_vertices(m);
  l.num_faces = num_faces(m);
  const std::vector<int> off = face_offsets(m);
  l.num_halfedges = m.face_vertices.size();
  const uint32_t n0 = m.face_sizes.empty() ? 0 : m.face_sizes[0];
  bool uniform = n0 == (rule == SubdivisionRule::Loop ? 3u : 4u);
  for (int n : m.face_sizes) uniform = uniform && uint32_t(n) == n0;
  if (uniform) {
    l.face_size = n0;
  } else {
    l.face_first.assign(off.begin(), off.end());
    l.next_of.resize(l.num_halfedges), l.prev_of.resize(l.num_halfedges), l.face_of.resize(l.num_halfedges);
    for (uint32_t f = 0; f < l.num_faces; ++f) {
      const uint32_t a = off[f], n = off[f + 1] - off[f];
      for (uint32_t i = 0; i < n; ++i) {
        l.next_of[a + i] = a + (i + 1) % n, l.prev_of[a + i] = a + (i + n - 1) % n, l.face_of[a + i] = f;
      }
    }
  }
  l.vert.assign(m.face_vertices.begin(), m.face_vertices.end());
  std::unordered_map<uint64_t, uint32_t> corner_of;
  corner_of.reserve(l.num_halfedges);
  for (uint32_t h = 0; h < l.num_halfedges; ++h) corner_of[edge_key(l.vert[h], l.vert[l.next(h)])] = h;
  l.twin.resize(l.num_halfedges), l.edge.resize(l.num_halfedges);
  bool open = false;
  for (uint32_t h = 0; h < l.num_halfedges; ++h) {
    auto it = corner_of.find(edge_key(l.vert[l.next(h)], l.vert[h]));
    l.twin[h] = it == corner_of.end() ? kNone : it->second;
    open = open || l.twin[h] == kNone;
    l.edge[h] = l.twin[h] != kNone && l.twin[h] < h ? l.edge[l.twin[h]] : l.num_edges++;
  }
  if (open && m.boundary == BoundaryRule::None)
    throw InputError(m.source, "boundary rule \"none\" makes OpenSubdiv leave the faces at the boundary out as holes, "
                               "which the halfedge rules do not take");
  index_edges_and_vertices(l);
  check_manifold_vertices(m, l);
  base_sharpness(m, l, corner_of);
  return l;
}

Hierarchy refine(const ControlMesh& m, SubdivisionRule rule, int depth) {
  Hierarchy r;
  r.rule = rule;
  r.levels.push_back(base_level(m, rule, &r.base_vertices));
  for (int d = 0; d < depth; ++d) {
    const Level& p = r.levels.back();
    Level c = rule == SubdivisionRule::Loop ? refine_loop(p) : refine_catmark(p);
    index_edges_and_vertices(c);
    refine_sharpness(m, p, c);
    // Once every crease has decayed the level is smooth: the rules' smooth path from here on.
    const auto sharp = [](const std::vector<float>& s) { return std::any_of(s.begin(), s.end(), [](float x) { return x > 0; }); };
    if (!sharp(c.edge_sharpness) && !sharp(c.vertex_sharpness)) c.edge_sharpness.clear(), c.vertex_sharpness.clear();
    r.creased.push_back(!p.edge_sharpness.empty());
    r.levels.push_back(std::move(c));
  }
  return r;
}

Counts counts_at(const ControlMesh& m, SubdivisionRule rule, int depth) {
  std::map<std::pair<int, int>, int> edges;
  const std::vector<int> off = face_offsets(m);
  for (int f = 0; f < num_faces(m); ++f)
    for (int i = off[f]; i < off[f + 1]; ++i) {
      const int a = m.face_vertices[i], b = m.face_vertices[i + 1 < off[f + 1] ? i + 1 : off[f]];
      edges[{std::min(a, b), std::max(a, b)}] = 1;
    }
  Counts c{double(m.face_vertices.size()), double(num_vertices(m)), double(edges.size()), double(num_faces(m))};
  for (int d = 0; d < depth; ++d) {
    const Counts p = c;
    c.halfedges = 4 * p.halfedges;
    c.edges = 2 * p.edges + p.halfedges;
    c.faces = rule == SubdivisionRule::Loop ? 4 * p.faces : p.halfedges;
    c.vertices = p.vertices + p.edges + (rule == SubdivisionRule::Loop ? 0 : p.faces);
  }
  return c;
}

}  // namespace sdb::halfedge
