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
  Components loops(f.vertices), parts(f.vertices);
  for (const auto& [key, use] : edges) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    ++valence[a];
    ++valence[b];
    parts.join(a, b);
    if (use.faces == 1) {
      ++f.boundary_edges;
      on_boundary[a] = on_boundary[b] = 1;
      loops.join(a, b);
    }
    if (use.faces > 2) ++f.non_manifold_edges;
    else if (use.forward > 1 || use.backward > 1) ++f.inconsistent_edges;
  }
  int used = 0, extraordinary = 0;
  std::vector<char> loop_root(f.vertices, 0), part_root(f.vertices, 0);
  const int interior_regular = f.all_triangles ? 6 : 4, boundary_regular = f.all_triangles ? 4 : 3;
  for (int v = 0; v < f.vertices; ++v) {
    if (valence[v] == 0) {
      ++f.unused_vertices;
      continue;
    }
    ++used;
    ++f.valences[valence[v]];
    if (valence[v] != (on_boundary[v] ? boundary_regular : interior_regular)) ++extraordinary;
    if (on_boundary[v] && !loop_root[loops.find(v)]) loop_root[loops.find(v)] = 1, ++f.boundary_loops;
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
}

}  // namespace sdb
