#include "harness/mesh/facts.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <unordered_map>

#include "harness/core/errors.h"

namespace sdb {
namespace {

uint64_t edge_key(int a, int b) { return (uint64_t(std::min(a, b)) << 32) | uint32_t(std::max(a, b)); }

struct EdgeUse {
  int faces = 0;
  int forward = 0;   // traversed min->max
  int backward = 0;  // traversed max->min
  int first_bad_face = -1;
};

using EdgeTable = std::unordered_map<uint64_t, EdgeUse>;

EdgeTable edge_table(const ControlMesh& m) {
  EdgeTable edges;
  edges.reserve(m.face_vertices.size());
  const auto off = face_offsets(m);
  for (int f = 0; f < num_faces(m); ++f) {
    const int n = m.face_sizes[f];
    for (int k = 0; k < n; ++k) {
      const int a = m.face_vertices[off[f] + k], b = m.face_vertices[off[f] + (k + 1) % n];
      if (a == b) continue;  // a degenerate face's collapsed edge is not an edge
      EdgeUse& e = edges[edge_key(a, b)];
      ++e.faces;
      (a < b ? e.forward : e.backward) += 1;
      if (e.first_bad_face < 0 && (e.faces > 2 || e.forward > 1 || e.backward > 1)) e.first_bad_face = f;
    }
  }
  return edges;
}

// Union-find over vertices, for components and boundary loops.
struct Components {
  std::vector<int> parent;
  explicit Components(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(int a, int b) { parent[find(a)] = find(b); }
};

// The fans of faces around each vertex: face corners (indices into face_vertices) joined when
// their faces share an edge at that corner's vertex. A vertex whose corners form more than one
// fan is pinched; a boundary loop runs through one fan of each vertex it passes.
struct Fans {
  Components corners;
  explicit Fans(const ControlMesh& m) : corners(static_cast<int>(m.face_vertices.size())) {
    const auto off = face_offsets(m);
    std::unordered_map<uint64_t, std::pair<int, int>> first_use;  // edge -> corner of its smaller vertex, and of the other
    for (int f = 0; f < num_faces(m); ++f) {
      const int n = m.face_sizes[f];
      for (int k = 0; k < n; ++k) {
        const int ca = off[f] + k, cb = off[f] + (k + 1) % n;
        const int a = m.face_vertices[ca], b = m.face_vertices[cb];
        if (a == b) continue;
        const std::pair<int, int> by_vertex = a < b ? std::pair{ca, cb} : std::pair{cb, ca};
        auto [it, first] = first_use.try_emplace(edge_key(a, b), by_vertex);
        if (first) continue;
        corners.join(it->second.first, by_vertex.first);
        corners.join(it->second.second, by_vertex.second);
      }
    }
  }
};

// Per vertex, the number of fans of faces around it (0 for unused vertices).
std::vector<int> fans_per_vertex(const ControlMesh& m, Fans& fans) {
  std::vector<int> count(m.positions.size(), 0);
  std::vector<char> root_seen(m.face_vertices.size(), 0);
  for (size_t c = 0; c < m.face_vertices.size(); ++c) {
    const int r = fans.corners.find(static_cast<int>(c));
    if (!root_seen[r]) root_seen[r] = 1, ++count[m.face_vertices[c]];
  }
  return count;
}

// Boundary loops: boundary edges (used by one face) joined where they meet in one fan, so that a
// bowtie's two triangles are two loops, not one through the pinch.
int count_boundary_loops(const ControlMesh& m, const EdgeTable& edges, Fans& fans) {
  const auto off = face_offsets(m);
  Components loops(static_cast<int>(m.face_vertices.size()));
  std::vector<char> on_loop(m.face_vertices.size(), 0);
  for (int f = 0; f < num_faces(m); ++f) {
    const int n = m.face_sizes[f];
    for (int k = 0; k < n; ++k) {
      const int ca = off[f] + k, cb = off[f] + (k + 1) % n;
      const int a = m.face_vertices[ca], b = m.face_vertices[cb];
      if (a == b || edges.at(edge_key(a, b)).faces != 1) continue;
      const int ra = fans.corners.find(ca), rb = fans.corners.find(cb);
      loops.join(ra, rb);
      on_loop[ra] = on_loop[rb] = 1;
    }
  }
  int count = 0;
  std::vector<char> loop_seen(m.face_vertices.size(), 0);
  for (size_t c = 0; c < on_loop.size(); ++c)
    if (on_loop[c] && !loop_seen[loops.find(static_cast<int>(c))]) loop_seen[loops.find(static_cast<int>(c))] = 1, ++count;
  return count;
}

// First face that repeats a vertex, and the vertex, or {-1, -1}.
std::pair<int, int> first_degenerate_face(const ControlMesh& m, int* count) {
  std::pair<int, int> first{-1, -1};
  const auto off = face_offsets(m);
  for (int f = 0; f < num_faces(m); ++f) {
    bool degenerate = false;
    for (int k = off[f]; k < off[f + 1]; ++k)
      for (int j = off[f]; j < k; ++j)
        if (m.face_vertices[j] == m.face_vertices[k] && !degenerate) {
          degenerate = true;
          if (first.first < 0) first = {f, m.face_vertices[k]};
        }
    if (count) *count += degenerate;
  }
  return first;
}

}  // namespace

double signed_volume6(const ControlMesh& m) {
  double v = 0;
  const auto off = face_offsets(m);
  for (int f = 0; f < num_faces(m); ++f)
    for (int k = 1; k + 1 < m.face_sizes[f]; ++k) {
      const auto& a = m.positions[m.face_vertices[off[f]]];
      const auto& b = m.positions[m.face_vertices[off[f] + k]];
      const auto& c = m.positions[m.face_vertices[off[f] + k + 1]];
      v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
  return v;
}

std::vector<int> vertex_valences(const ControlMesh& m) {
  std::vector<int> valence(m.positions.size(), 0);
  for (const auto& [key, use] : edge_table(m)) {
    ++valence[key >> 32];
    ++valence[key & 0xffffffffu];
  }
  return valence;
}

MeshFacts compute_facts(const ControlMesh& m) {
  MeshFacts f;
  f.vertices = num_vertices(m);
  f.faces = num_faces(m);
  f.creased_edges = static_cast<int>(std::count_if(m.creases.begin(), m.creases.end(),
                                                   [](const EdgeCrease& c) { return c.sharpness > 0; }));
  f.corners = static_cast<int>(m.corners.size());
  f.holes = static_cast<int>(m.holes.size());
  for (int s : m.face_sizes) ++f.face_sizes[s];
  f.all_quads = f.face_sizes.size() == 1 && f.face_sizes.count(4);
  f.all_triangles = f.face_sizes.size() == 1 && f.face_sizes.count(3);

  first_degenerate_face(m, &f.degenerate_faces);
  const EdgeTable edges = edge_table(m);
  f.edges = static_cast<int>(edges.size());
  std::vector<int> valence(f.vertices, 0);
  std::vector<char> on_boundary(f.vertices, 0);
  Components parts(f.vertices);
  Fans fans(m);
  for (int n : fans_per_vertex(m, fans)) f.non_manifold_vertices += n > 1;
  f.boundary_loops = count_boundary_loops(m, edges, fans);
  for (const auto& [key, use] : edges) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    ++valence[a];
    ++valence[b];
    parts.join(a, b);
    if (use.faces == 1) {
      ++f.boundary_edges;
      on_boundary[a] = on_boundary[b] = 1;
    }
    if (use.faces > 2) ++f.non_manifold_edges;
    else if (use.forward > 1 || use.backward > 1) ++f.inconsistent_edges;
  }
  int used = 0, extraordinary = 0;
  std::vector<char> part_root(f.vertices, 0);
  const int interior_regular = f.all_triangles ? 6 : 4, boundary_regular = f.all_triangles ? 4 : 3;
  for (int v = 0; v < f.vertices; ++v) {
    if (valence[v] == 0) {
      ++f.unused_vertices;
      continue;
    }
    ++used;
    ++f.valences[valence[v]];
    if (valence[v] != (on_boundary[v] ? boundary_regular : interior_regular)) ++extraordinary;
    if (!part_root[parts.find(v)]) part_root[parts.find(v)] = 1, ++f.components;
  }
  f.extraordinary_vertex_fraction = used ? double(extraordinary) / used : 0.0;

  const auto off = face_offsets(m);
  int quads = 0, eq = 0;
  for (int face = 0; face < f.faces; ++face) {
    if (m.face_sizes[face] != 4) continue;
    ++quads;
    bool extra = false;
    for (int k = 0; k < 4; ++k) extra |= valence[m.face_vertices[off[face] + k]] != 4;
    eq += extra;
  }
  f.extraordinary_quad_fraction = quads ? double(eq) / quads : 0.0;

  f.euler = used - f.edges + f.faces;
  f.closed = f.boundary_edges == 0 && f.non_manifold_edges == 0;
  // chi = 2c - 2g - b for an orientable manifold with c components and b boundary loops.
  if (f.manifold()) f.genus = (2 * f.components - f.boundary_loops - f.euler) / 2;
  return f;
}

namespace {

// A pinched vertex (its faces form more than one fan) named at the first face of its second fan.
void require_one_fan(const ControlMesh& m, const std::string& needs) {
  Fans fans(m);
  const std::vector<int> count = fans_per_vertex(m, fans);
  const auto off = face_offsets(m);
  std::vector<int> first_root(m.positions.size(), -1);
  for (int f = 0; f < num_faces(m); ++f)
    for (int c = off[f]; c < off[f + 1]; ++c) {
      const int v = m.face_vertices[c], r = fans.corners.find(c);
      if (count[v] < 2) continue;
      if (first_root[v] < 0) first_root[v] = r;
      else if (first_root[v] != r) {
        const int base = m.source.ends_with(".obj") ? 1 : 0;
        throw InputError(face_location(m, f), "non-manifold vertex " + std::to_string(v + base) + ": its faces form " +
                                                  std::to_string(count[v]) + " fans that meet only there (a pinch)" + needs);
      }
    }
}

}  // namespace

void require_manifold(const ControlMesh& m, const std::string& scheme) {
  const std::string needs = "; " + scheme + " needs a manifold, oriented mesh";
  if (auto [face, v] = first_degenerate_face(m, nullptr); face >= 0) {
    const int base = m.source.ends_with(".obj") ? 1 : 0;
    throw InputError(face_location(m, face), "vertex " + std::to_string(v + base) + " repeated in one face" + needs);
  }
  const EdgeTable edges = edge_table(m);
  int worst_face = -1;
  std::string what;
  for (const auto& [key, use] : edges) {
    if (use.first_bad_face < 0 || (worst_face >= 0 && use.first_bad_face >= worst_face)) continue;
    worst_face = use.first_bad_face;
    const std::string edge = "(" + std::to_string((key >> 32) + 1) + "," + std::to_string((key & 0xffffffffu) + 1) + ")";
    what = use.faces > 2 ? "non-manifold edge " + edge + " shared by " + std::to_string(use.faces) + " faces"
                         : "inconsistent orientation: edge " + edge + " traversed twice in the same direction";
  }
  if (worst_face >= 0) throw InputError(face_location(m, worst_face), what + needs);
  require_one_fan(m, needs);
}

}  // namespace sdb
