#include "schemes/edgefriend/topology.h"

#include <opensubdiv/far/topologyLevel.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <unordered_map>

#include "harness/core/errors.h"

namespace sdb::edgefriend {
namespace {

namespace Far = OpenSubdiv::Far;
using refined::kInfiniteSharpness;

uint64_t edge_key(uint32_t a, uint32_t b) { return uint64_t(a) << 32 | b; }

// The quad across a quad's edge a -> b (the corner that runs b -> a), as a friend: that corner
// must be a friend's 0 or 2 (topology.h).
uint32_t friend_across(const std::unordered_map<uint64_t, uint32_t>& corner_of, uint32_t a, uint32_t b) {
  const auto it = corner_of.find(edge_key(b, a));
  if (it == corner_of.end() || (it->second & 1u)) throw std::logic_error("edgefriend: an edge without its friend");
  return 2 * (it->second >> 2) + ((it->second >> 1) & 1u);
}

// The ring walk through the friends (rules.cpp's), as a check that every vertex's quads form one
// closed fan: a vertex where two cones meet has more quads than its walk meets.
// Valences past the weight tables' are refused (a ghost face's point aside: never output).
void check_fans(const ControlMesh& m, const Level& l, uint32_t mesh_vertices) {
  std::vector<uint32_t> quads_at(l.num_vertices, 0);
  for (uint32_t v : l.indices) ++quads_at[v];
  for (uint32_t v = 0; v < mesh_vertices; ++v) {
    const uint32_t start = l.vertex_corner[v];
    if (start == kNone) continue;
    if (quads_at[v] > uint32_t(kMaxValence))
      throw InputError(m.source, "a vertex or face of " + std::to_string(quads_at[v]) + " edges, past the " +
                                     std::to_string(kMaxValence) + " the smooth rule's tables have");
    uint32_t c = start, visited = 0;
    do {
      ++visited;
      const Friends& f = l.friends[c >> 2];
      const uint32_t slot = c & 3u;
      c = 2 * (slot == 0 || slot == 3 ? f.friend1 : f.friend0) + (c & 1u);
    } while (c != start && visited <= quads_at[v]);
    if (visited != quads_at[v])
      throw InputError(m.source, "vertex " + std::to_string(v + 1) + " is not manifold: its faces form more than one fan, "
                                 "which Edge-Friend's ring walk does not take");
  }
}

}  // namespace

namespace {

// Level 1: OpenSubdiv's level-1 quads turned so that corner 0 is the child of the base vertex (the
// child face of base corner c is quad c, as coords.h numbers it), then one ghost quad per corner
// of each boundary loop's closing face: (v, the child of the boundary edge into v, the loop's
// face point, the child of the edge out of v), the loop's face point a new vertex.
Level first_level(const ControlMesh& m, const Far::TopologyRefiner& r, std::vector<std::vector<uint32_t>>& loops,
                  uint32_t& first_ghost_point) {
  const Far::TopologyLevel& l0 = r.GetLevel(0);
  const Far::TopologyLevel& l1 = r.GetLevel(1);
  const uint32_t V0 = l0.GetNumVertices(), F0 = l0.GetNumFaces(), R = l1.GetNumFaces();
  if (R != m.face_vertices.size()) throw std::logic_error("edgefriend: OpenSubdiv's level 1 has not one quad per base corner");
  Level l;
  l.mesh_quads = R;
  l.indices.resize(4 * uint64_t(R));
  std::vector<float> sharp(4 * uint64_t(R), 0.0f);  // the edge from each corner
  bool semi_sharp = false;
  for (uint32_t q = 0; q < R; ++q) {
    const Far::ConstIndexArray fv = l1.GetFaceVertices(int(q)), fe = l1.GetFaceEdges(int(q));
    int turn = 0;
    while (turn < 4 && uint32_t(fv[turn]) >= V0) ++turn;
    if (fv.size() != 4 || turn == 4 || uint32_t(fv[turn]) != uint32_t(m.face_vertices[q]) ||
        uint32_t(fv[(turn + 2) % 4]) < V0 || uint32_t(fv[(turn + 2) % 4]) >= V0 + F0)
      throw std::logic_error("edgefriend: OpenSubdiv's level 1 is not numbered as expected");
    for (int i = 0; i < 4; ++i) {
      const int e = fe[(turn + i) % 4];
      l.indices[4 * q + i] = fv[(turn + i) % 4];
      float s = l1.IsEdgeBoundary(e) ? kInfiniteSharpness : l1.GetEdgeSharpness(e);
      sharp[4 * q + i] = s;
      semi_sharp = semi_sharp || (s > 0.0f && s < kInfiniteSharpness);
    }
  }
  if (m.crease_method == CreaseMethod::Chaikin && semi_sharp)
    throw InputError(m.source, "Chaikin creasing with semi-sharp creases left after the first step: Edge-Friend decays "
                               "every edge's sharpness by one a level (uniform creasing), Chaikin's rule averages it with its neighbours'");
  std::unordered_map<uint64_t, uint32_t> corner_of;
  corner_of.reserve(4 * uint64_t(R) + 64);
  for (uint32_t c = 0; c < 4 * R; ++c) corner_of[edge_key(l.indices[c], l.indices[(c & ~3u) | ((c + 1) & 3u)])] = c;
  // Boundary edges: the child edge into base vertex v (corner 3 -> 0) and out of it (0 -> 1).
  std::unordered_map<uint32_t, uint32_t> into, out_of, from;  // v -> child edge point; edge point -> v
  for (uint32_t c = 0; c < 4 * R; ++c) {
    const uint32_t a = l.indices[c], b = l.indices[(c & ~3u) | ((c + 1) & 3u)];
    if (corner_of.count(edge_key(b, a))) continue;
    const bool out = (c & 3u) == 0;
    if (!out && (c & 3u) != 3) throw std::logic_error("edgefriend: a boundary edge inside a base face");
    const uint32_t v = out ? a : b, e = out ? b : a;
    if (!(out ? out_of : into).emplace(v, e).second)
      throw InputError(m.source, "vertex " + std::to_string(v + 1) + " is not manifold: it is on more than one boundary "
                                 "fan, which Edge-Friend's ring walk does not take");
    if (out) from[e] = v;
  }
  if (!into.empty() && m.boundary == BoundaryRule::None)
    throw InputError(m.source, "boundary rule \"none\" makes OpenSubdiv leave the faces at the boundary out as holes, "
                               "which Edge-Friend does not take");
  first_ghost_point = l1.GetNumVertices();
  std::vector<uint32_t> boundary;
  for (const auto& [v, e] : into) boundary.push_back(v);
  std::sort(boundary.begin(), boundary.end());  // loops in a fixed order (the map's is not)
  std::unordered_map<uint32_t, char> done;
  for (uint32_t v0 : boundary) {
    if (done.count(v0)) continue;
    const uint32_t ghost_point = first_ghost_point + uint32_t(loops.size());
    loops.emplace_back();
    uint32_t v = v0;
    do {
      done[v] = 1;
      loops.back().push_back(v);
      const uint32_t in = into.at(v), out = out_of.at(v);
      const uint32_t q = uint32_t(l.indices.size() / 4);
      for (uint32_t x : {v, in, ghost_point, out}) l.indices.push_back(x);
      for (float s : {kInfiniteSharpness, 0.0f, 0.0f, kInfiniteSharpness}) sharp.push_back(s);
      for (uint32_t i = 0; i < 4; ++i) corner_of[edge_key(l.indices[4 * q + i], l.indices[4 * q + (i + 1) % 4])] = 4 * q + i;
      v = from.at(in);  // the ghost face's next corner: the other end of the boundary edge into v
    } while (v != v0);
  }
  l.num_quads = uint32_t(l.indices.size() / 4);
  l.num_vertices = first_ghost_point + uint32_t(loops.size());
  l.friends.resize(l.num_quads);
  for (uint32_t q = 0; q < l.num_quads; ++q) {
    const uint32_t* x = &l.indices[4 * q];
    l.friends[q] = {friend_across(corner_of, x[1], x[2]), sharp[4 * q + 1], friend_across(corner_of, x[3], x[0]), sharp[4 * q + 3]};
    l.creased = l.creased || sharp[4 * q + 1] > 0 || sharp[4 * q + 3] > 0;
  }
  l.vertex_corner.assign(l.num_vertices, kNone);
  for (uint32_t c = 4 * l.num_quads; c-- > 0;) l.vertex_corner[l.indices[c]] = c;
  std::vector<float> vs(l.num_vertices, 0.0f);
  bool corners = false;
  for (uint32_t v = 0; v < uint32_t(l1.GetNumVertices()); ++v) vs[v] = l1.GetVertexSharpness(int(v)), corners = corners || vs[v] > 0;
  if (corners) l.vertex_sharpness = std::move(vs), l.creased = true;
  check_fans(m, l, first_ghost_point);
  return l;
}

// One level's topology from the one before: the topology half of the paper's kernel (Listing 1),
// one quad at a time; every entry is written by exactly one quad.
Level refine_level(const Level& p) {
  const uint32_t Q = p.num_quads;
  Level c;
  c.num_quads = 4 * Q;
  c.mesh_quads = 4 * p.mesh_quads;
  c.num_vertices = vertices_after(p.num_vertices, Q);
  c.indices.resize(16 * uint64_t(Q));
  c.friends.resize(4 * uint64_t(Q));
  c.vertex_corner.assign(c.num_vertices, kNone);
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, Q, 4096), [&](const tbb::blocked_range<uint32_t>& range) {
    for (uint32_t q = range.begin(); q < range.end(); ++q) {
      const uint32_t* x = &p.indices[4 * uint64_t(q)];
      const Friends& f = p.friends[q];
      const uint32_t face = 4 * q + 1, on0 = 4 * q + 2, on1 = 4 * q + 3;
      const uint32_t q0 = 4 * (f.friend0 >> 1), s0 = f.friend0 & 1u, q1 = 4 * (f.friend1 >> 1), s1 = f.friend1 & 1u;
      const uint32_t off0 = q0 + 2 + s0, off1 = q1 + 2 + s1;  // the points of the owned edges 1-2 and 3-0
      const uint32_t quads[4][4] = {{child_of_vertex(x[0], Q), on0, face, off1},
                                    {child_of_vertex(x[1], Q), off0, face, on0},
                                    {child_of_vertex(x[2], Q), on1, face, off0},
                                    {child_of_vertex(x[3], Q), off1, face, on1}};
      std::copy(&quads[0][0], &quads[0][0] + 16, &c.indices[16 * uint64_t(q)]);
      const float h0 = decay(f.sharpness0), h1 = decay(f.sharpness1);
      Friends* n = &c.friends[4 * uint64_t(q)];
      // Children 0 and 2 own the halves of edges 3-0 and 1-2 at corners 0 and 2; the halves at
      // corners 1 and 3 are owned by the friends' children, whose friend this quad's children are.
      n[0] = {2 * (4 * q + 1) + 1, 0.0f, 2 * (q1 + 2 * s1) + 0, h1};
      n[1].friend0 = 2 * (4 * q + 2) + 1, n[1].sharpness0 = 0.0f;
      n[2] = {2 * (4 * q + 3) + 1, 0.0f, 2 * (q0 + 2 * s0) + 0, h0};
      n[3].friend0 = 2 * (4 * q + 0) + 1, n[3].sharpness0 = 0.0f;
      c.friends[q0 + 2 * s0 + 1].friend1 = 2 * (4 * q + 1) + 0, c.friends[q0 + 2 * s0 + 1].sharpness1 = h0;
      c.friends[q1 + 2 * s1 + 1].friend1 = 2 * (4 * q + 3) + 0, c.friends[q1 + 2 * s1 + 1].sharpness1 = h1;
      c.vertex_corner[face] = 4 * (4 * q) + 2;
      c.vertex_corner[off0] = 4 * (q0 + 2 * s0) + 1;
      c.vertex_corner[off1] = 4 * (q1 + 2 * s1) + 1;
    }
  });
  for (uint32_t v = 0; v < p.num_vertices; ++v)
    if (p.vertex_corner[v] != kNone) c.vertex_corner[child_of_vertex(v, Q)] = 4 * p.vertex_corner[v];
  if (!p.vertex_sharpness.empty()) {
    c.vertex_sharpness.assign(c.num_vertices, 0.0f);
    for (uint32_t v = 0; v < p.num_vertices; ++v) c.vertex_sharpness[child_of_vertex(v, Q)] = decay(p.vertex_sharpness[v]);
  }
  for (const Friends& f : c.friends) c.creased = c.creased || f.sharpness0 > 0 || f.sharpness1 > 0;
  const auto sharp = [](float s) { return s > 0.0f; };
  if (std::none_of(c.vertex_sharpness.begin(), c.vertex_sharpness.end(), sharp)) c.vertex_sharpness.clear();
  c.creased = c.creased || !c.vertex_sharpness.empty();
  return c;
}

// A level's mesh quads as faces, corners numbered by `out`: twins (kNone at the mesh's boundary)
// and, where the level is creased, each corner's edge sharpness.
void quad_faces(const Level& l, const std::function<uint32_t(uint32_t)>& out, std::vector<uint32_t>& verts,
                std::vector<uint32_t>& twin, std::vector<float>& edge_sharpness) {
  const uint32_t R = l.mesh_quads;
  verts.resize(4 * uint64_t(R));
  for (uint64_t c = 0; c < 4 * uint64_t(R); ++c) verts[c] = out(l.indices[c]);
  twin.assign(4 * uint64_t(R), kNone);
  if (l.creased) edge_sharpness.assign(4 * uint64_t(R), 0.0f);
  for (uint32_t q = 0; q < l.num_quads; ++q) {
    const Friends& f = l.friends[q];
    const uint32_t owned[2][3] = {{4 * q + 1, f.friend0, 0}, {4 * q + 3, f.friend1, 1}};
    for (const auto& [corner, fr, which] : owned) {
      const uint32_t other = 4 * (fr >> 1) + 2 * (fr & 1u);
      const float s = which ? f.sharpness1 : f.sharpness0;
      if (q < R && (fr >> 1) < R) twin[corner] = other, twin[other] = corner;
      if (edge_sharpness.empty()) continue;
      if (q < R) edge_sharpness[corner] = s;
      if ((fr >> 1) < R) edge_sharpness[other] = s;
    }
  }
}

// The last level's mesh quads as the output's faces (topology.h, Hierarchy).
void lay_out(Hierarchy& h) {
  const Level& l = h.levels.back();
  const uint32_t R = l.mesh_quads;
  std::vector<char> used(l.num_vertices, 0);
  for (uint64_t c = 0; c < 4 * uint64_t(R); ++c) used[l.indices[c]] = 1;
  h.out_vertices = uint32_t(std::count(used.begin(), used.end(), 1));
  if (h.out_vertices != l.num_vertices) {
    h.out_index.assign(l.num_vertices, kNone);
    for (uint32_t v = 0, k = 0; v < l.num_vertices; ++v)
      if (used[v]) h.out_index[v] = k++;
  }
  const auto out = [&](uint32_t v) { return h.out_index.empty() ? v : h.out_index[v]; };
  quad_faces(l, out, h.out_verts, h.out_twin, h.out_edge_sharpness);
  if (!l.vertex_sharpness.empty()) {
    h.out_vertex_sharpness.assign(h.out_vertices, 0.0f);
    for (uint32_t v = 0; v < l.num_vertices; ++v)
      if (out(v) != kNone && used[v]) h.out_vertex_sharpness[out(v)] = l.vertex_sharpness[v];
  }
}

}  // namespace

namespace {

// Quads as a FaceLevel over the arrays (which outlive it).
refined::FaceLevel quad_level(uint32_t vertices, const std::vector<uint32_t>& verts, const std::vector<uint32_t>& twin,
                              const std::vector<float>& edge_sharpness, const std::vector<float>& vertex_sharpness) {
  refined::FaceLevel f;
  f.face_size = 4;
  f.num_vertices = vertices;
  f.verts = verts.data();
  f.twin = twin.data();
  f.num_corners = verts.size();
  if (!edge_sharpness.empty()) f.edge_sharpness = [&edge_sharpness](uint32_t c) { return edge_sharpness[c]; };
  if (!vertex_sharpness.empty()) f.vertex_sharpness = [&vertex_sharpness](uint32_t v) { return vertex_sharpness[v]; };
  return f;
}

}  // namespace

refined::FaceLevel Hierarchy::face_level() const {
  return quad_level(out_vertices, out_verts, out_twin, out_edge_sharpness, out_vertex_sharpness);
}

FirstLevelFaces first_level_faces(const Hierarchy& h) {
  FirstLevelFaces f;
  const Level& l = h.levels.front();
  quad_faces(l, [](uint32_t v) { return v; }, f.verts, f.twin, f.edge_sharpness);
  f.vertex_sharpness = l.vertex_sharpness;
  f.last_of.resize(l.num_vertices);
  for (uint32_t v = 0; v < l.num_vertices; ++v) {
    uint32_t w = v;
    for (size_t d = 0; d + 1 < h.levels.size(); ++d) w = child_of_vertex(w, h.levels[d].num_quads);
    f.last_of[v] = h.out_index.empty() ? w : h.out_index[w];
  }
  return f;
}

refined::FaceLevel FirstLevelFaces::face_level() const {
  return quad_level(static_cast<uint32_t>(last_of.size()), verts, twin, edge_sharpness, vertex_sharpness);
}

Hierarchy refine(const ControlMesh& m, const Far::TopologyRefiner& level1, int depth) {
  Hierarchy h;
  h.levels.push_back(first_level(m, level1, h.loops, h.first_ghost_point));
  for (int d = 1; d < depth; ++d) h.levels.push_back(refine_level(h.levels.back()));
  lay_out(h);
  return h;
}

Counts counts_at(const ControlMesh& m, int depth) {
  std::unordered_map<uint64_t, char> directed;
  directed.reserve(m.face_vertices.size());
  const std::vector<int> off = face_offsets(m);
  for (int f = 0; f < num_faces(m); ++f)
    for (int i = off[f]; i < off[f + 1]; ++i)
      directed[edge_key(m.face_vertices[i], m.face_vertices[i + 1 < off[f + 1] ? i + 1 : off[f]])] = 1;
  double boundary = 0, edges = 0;
  for (const auto& [key, x] : directed) {
    const bool paired = directed.count(key >> 32 | key << 32);
    boundary += !paired;
    edges += paired ? 0.5 : 1.0;
  }
  // Level 1: a quad per corner and per boundary edge (the ghosts); at most one ghost point per boundary edge.
  Counts c{double(m.face_vertices.size()) + boundary, double(num_vertices(m)) + edges + num_faces(m) + boundary};
  for (int d = 1; d < depth; ++d) c = {4 * c.quads, 3 * c.quads + std::max(c.vertices, c.quads)};
  return c;
}

}  // namespace sdb::edgefriend
