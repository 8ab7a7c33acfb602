#include "harness/reference/bfr_defect.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace sdb {
namespace {

using Edge = std::pair<int, int>;

Edge edge_key(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

// Each edge's faces, as (edge, face) sorted by edge: a map per edge costs too much on big meshes.
struct Adjacency {
  std::vector<int> offsets;
  std::vector<std::pair<Edge, int>> edge_faces;
  std::vector<std::pair<Edge, float>> sharpness;  // sorted by edge

  std::pair<size_t, size_t> faces_of(Edge e) const {
    const auto lo = std::lower_bound(edge_faces.begin(), edge_faces.end(), std::make_pair(e, -1));
    auto hi = lo;
    while (hi != edge_faces.end() && hi->first == e) ++hi;
    return {size_t(lo - edge_faces.begin()), size_t(hi - edge_faces.begin())};
  }
  bool creased(Edge e) const {
    const auto it = std::lower_bound(sharpness.begin(), sharpness.end(), std::make_pair(e, -1.0f));
    return it != sharpness.end() && it->first == e && it->second > 0;
  }
};

Adjacency adjacency_of(const ControlMesh& m) {
  Adjacency a;
  a.offsets = face_offsets(m);
  a.edge_faces.reserve(m.face_vertices.size());
  for (int f = 0; f < num_faces(m); ++f)
    for (int i = a.offsets[f]; i < a.offsets[f + 1]; ++i) {
      const int next = i + 1 < a.offsets[f + 1] ? i + 1 : a.offsets[f];
      a.edge_faces.push_back({edge_key(m.face_vertices[i], m.face_vertices[next]), f});
    }
  std::sort(a.edge_faces.begin(), a.edge_faces.end());
  for (const auto& c : m.creases) a.sharpness.push_back({edge_key(c.v0, c.v1), c.sharpness});
  std::sort(a.sharpness.begin(), a.sharpness.end());
  return a;
}

// The vertex before and after `v` in face `f` (v's first occurrence).
std::pair<int, int> neighbours_in_face(const ControlMesh& m, const Adjacency& a, int f, int v) {
  const int b = a.offsets[f], n = a.offsets[f + 1] - b;
  for (int i = 0; i < n; ++i)
    if (m.face_vertices[b + i] == v) return {m.face_vertices[b + (i + n - 1) % n], m.face_vertices[b + (i + 1) % n]};
  return {-1, -1};
}

struct Fan {
  bool closed = false;
  int faces = 0;
};

// The faces around `v` reachable from `f` across edges with exactly two faces.
Fan fan_of(const ControlMesh& m, const Adjacency& a, int f, int v) {
  Fan fan{false, 1};
  int face = f, from = neighbours_in_face(m, a, f, v).first;  // leave through the edge after v
  for (int guard = 0; guard < 1 << 20; ++guard) {
    const auto [prev, next] = neighbours_in_face(m, a, face, v);
    const int out = prev == from ? next : prev;
    const auto [lo, hi] = a.faces_of(edge_key(v, out));
    if (hi - lo != 2) break;
    const int other = a.edge_faces[lo].second == face ? a.edge_faces[lo + 1].second : a.edge_faces[lo].second;
    if (other == f) {
      fan.closed = true;
      return fan;
    }
    face = other, from = out, ++fan.faces;
  }
  return fan;
}

// Vertices with an edge that is creased or has more than two faces (infinitely sharp to Bfr).
std::vector<char> sharp_vertices(const ControlMesh& m, const Adjacency& a) {
  std::vector<char> sharp(m.positions.size(), 0);
  for (size_t i = 0; i < a.edge_faces.size();) {
    const Edge e = a.edge_faces[i].first;
    const auto [lo, hi] = a.faces_of(e);
    if (hi - lo > 2 || a.creased(e)) sharp[e.first] = sharp[e.second] = 1;
    i = hi;
  }
  return sharp;
}

}  // namespace

std::optional<std::string> bfr_overlapping_patch_defect(const ControlMesh& m) {
  const Adjacency a = adjacency_of(m);
  const std::vector<char> sharp = sharp_vertices(m, a);
  for (int f = 0; f < num_faces(m); ++f) {
    bool two_face_closed = false, open = false, sharp_corner = false;
    for (int i = a.offsets[f]; i < a.offsets[f + 1]; ++i) {
      const Fan fan = fan_of(m, a, f, m.face_vertices[i]);
      two_face_closed |= fan.closed && fan.faces == 2;
      open |= !fan.closed;
      sharp_corner |= sharp[m.face_vertices[i]] != 0;
    }
    if (two_face_closed && open && sharp_corner)
      return face_location(m, f) +
             ": OpenSubdiv 3.5.0's Bfr builds this face's patch from uninitialised memory (a corner closed by two "
             "faces beside a boundary and a sharp edge; fixed in OpenSubdiv 3.5.1)";
  }
  return std::nullopt;
}

}  // namespace sdb
