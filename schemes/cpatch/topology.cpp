#include "schemes/cpatch/topology.h"

#include <cmath>
#include <numbers>
#include <string>
#include <unordered_map>

#include "harness/core/errors.h"

namespace sdb::cpatch {
namespace {

uint64_t edge_key(int a, int b) { return (uint64_t(uint32_t(a)) << 32) | uint32_t(b); }

// Directed edge (q_i, q_{i+1}) -> corner id 4q + i.
std::unordered_map<uint64_t, int> directed_edges(const ControlMesh& mesh) {
  std::unordered_map<uint64_t, int> edges;
  edges.reserve(mesh.face_vertices.size() * 2);
  for (int q = 0; q < num_faces(mesh); ++q)
    for (int i = 0; i < 4; ++i) {
      const int a = mesh.face_vertices[4 * q + i], b = mesh.face_vertices[4 * q + (i + 1) % 4];
      if (!edges.emplace(edge_key(a, b), 4 * q + i).second)
        throw InputError(face_location(mesh, q), "edge " + std::to_string(a) + "-" + std::to_string(b) +
                                                     " is used twice in the same direction (non-manifold)");
    }
  return edges;
}

void require_quads(const ControlMesh& mesh) {
  for (int f = 0; f < num_faces(mesh); ++f)
    if (mesh.face_sizes[f] != 4)
      throw InputError(face_location(mesh, f), "c-patch conversion needs an all-quad mesh (quadrangulate first)");
}

// Orders the quads around every vertex counter-clockwise (Figure 5) and assigns slots.
void build_neighbourhoods(const ControlMesh& mesh, CpatchTopology& t) {
  const auto edges = directed_edges(mesh);
  const int nv = num_vertices(mesh);
  std::vector<int> first_corner(nv, -1), incident(nv, 0);
  for (int c = 0; c < 4 * t.num_quads; ++c) {
    const int v = t.quad_vertices[c];
    if (first_corner[v] < 0) first_corner[v] = c;
    ++incident[v];
  }
  auto corner_vertex = [&](int c, int offset) { return t.quad_vertices[(c & ~3) + ((c & 3) + offset) % 4]; };

  // Walk each fan: sector j+1 is the quad holding the directed edge p* -> (corner i-1 of sector j).
  std::vector<std::vector<int>> fans(nv);
  for (int v = 0; v < nv; ++v) {
    if (first_corner[v] < 0) continue;
    int c = first_corner[v];
    do {
      fans[v].push_back(c);
      const auto it = edges.find(edge_key(v, corner_vertex(c, 3)));
      if (it == edges.end())
        throw InputError(face_location(mesh, c / 4), "edge " + std::to_string(corner_vertex(c, 3)) + "-" +
                                                         std::to_string(v) +
                                                         " is a boundary edge; c-patches need a closed mesh");
      c = it->second;
    } while (c != first_corner[v] && static_cast<int>(fans[v].size()) <= incident[v]);
    if (static_cast<int>(fans[v].size()) != incident[v])
      throw InputError(mesh.source,
                       "vertex " + std::to_string(v) + " has more than one fan of quads (non-manifold vertex)");
    if (incident[v] < 3)
      throw InputError(mesh.source, "vertex " + std::to_string(v) + " has valence " + std::to_string(incident[v]) +
                                        "; c-patches need valence 3 or more");
  }

  t.first_slot.assign(nv + 1, 0);
  t.valence.assign(nv, 0);
  for (int v = 0; v < nv; ++v) {
    t.valence[v] = static_cast<int>(fans[v].size());
    t.first_slot[v + 1] = t.first_slot[v] + t.valence[v];
  }
  t.ring.assign(2 * t.first_slot[nv], 0);
  t.corners.assign(4 * t.num_quads, {});
  for (int v = 0; v < nv; ++v) {
    const int n = t.valence[v];
    for (int j = 0; j < n; ++j) {
      const int c = fans[v][j], slot = t.first_slot[v] + j;
      t.ring[2 * slot] = corner_vertex(c, 1);
      t.ring[2 * slot + 1] = corner_vertex(c, 2);
      t.corners[c] = {v, slot, t.first_slot[v] + (j + 1) % n};
    }
  }
}

void build_valence_constants(CpatchTopology& t) {
  t.max_valence = 0;
  for (int n : t.valence) t.max_valence = std::max(t.max_valence, n);
  t.valence_constants.assign(t.max_valence + 1, {});
  t.trig_cos.clear();
  t.trig_sin.clear();
  for (int n = 3; n <= t.max_valence; ++n) {
    const double angle = 2.0 * std::numbers::pi / n;
    ValenceConstants& k = t.valence_constants[n];
    k.cos_n = static_cast<float>(std::cos(angle));
    k.sin_n = static_cast<float>(std::sin(angle));
    k.sigma = static_cast<float>(subdominant_eigenvalue(n));
    k.tangent_scale = static_cast<float>(1.0 / (n * subdominant_eigenvalue(n)));
    k.limit_scale = static_cast<float>(1.0 / (n * (n + 5.0)));
    k.trig_offset = static_cast<int>(t.trig_cos.size());
    for (int j = 0; j < n; ++j) {
      t.trig_cos.push_back(static_cast<float>(std::cos(angle * j)));
      t.trig_sin.push_back(static_cast<float>(std::sin(angle * j)));
    }
  }
}

// Table 2's valence-dependent weights for corner i of a quad with corner valences n[0..3].
CpatchCornerWeights corner_weights(const int n[4], int i) {
  const double c_i = std::cos(2.0 * std::numbers::pi / n[i]),
               c_next = std::cos(2.0 * std::numbers::pi / n[(i + 1) % 4]);
  const double s_i = std::sin(2.0 * std::numbers::pi / n[i]),
               s_next = std::sin(2.0 * std::numbers::pi / n[(i + 1) % 4]);
  return {static_cast<float>((1.0 + c_i) / 4.0), static_cast<float>((1.0 - c_next) / 8.0),
          static_cast<float>((1.0 + c_next) / 4.0), static_cast<float>((1.0 - c_i) / 8.0),
          static_cast<float>(3.0 / (4.0 * (s_i + s_next)))};
}

void classify_quads(CpatchTopology& t) {
  t.extraordinary.assign(t.num_quads, 0);
  t.forward_sides.assign(t.num_quads, 0);
  t.ordinary_quads.clear();
  t.extraordinary_quads.clear();
  t.cpatch_weights.clear();
  t.extraordinary_index.assign(t.num_quads, -1);
  for (int q = 0; q < t.num_quads; ++q) {
    int n[4];
    for (int i = 0; i < 4; ++i) n[i] = t.valence[t.quad_vertices[4 * q + i]];
    for (int i = 0; i < 4; ++i)
      if (t.quad_vertices[4 * q + i] < t.quad_vertices[4 * q + (i + 1) % 4]) t.forward_sides[q] |= uint8_t(1u << i);
    t.extraordinary[q] = (n[0] != 4 || n[1] != 4 || n[2] != 4 || n[3] != 4) ? 1 : 0;
    if (!t.extraordinary[q]) {
      t.ordinary_quads.push_back(q);
      continue;
    }
    t.extraordinary_index[q] = static_cast<int>(t.extraordinary_quads.size());
    t.extraordinary_quads.push_back(q);
    for (int i = 0; i < 4; ++i) t.cpatch_weights.push_back(corner_weights(n, i));
  }
}

}  // namespace

double subdominant_eigenvalue(int n) {
  const double c = std::cos(2.0 * std::numbers::pi / n);
  return (c + 5.0 + std::sqrt((c + 9.0) * (c + 1.0))) / 16.0;
}

CpatchTopology build_topology(const ControlMesh& quads) {
  require_quads(quads);
  CpatchTopology t;
  t.num_vertices = num_vertices(quads);
  t.num_quads = num_faces(quads);
  t.quad_vertices = quads.face_vertices;
  build_neighbourhoods(quads, t);
  build_valence_constants(t);
  classify_quads(t);
  return t;
}

}  // namespace sdb::cpatch
