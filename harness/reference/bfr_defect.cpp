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
  std::vector<std::pair<Edge, std::pair<int, int>>> edge_faces;  // (face, slot of the edge's first vertex)
  std::vector<std::pair<Edge, float>> sharpness;  // sorted by edge

  std::pair<size_t, size_t> faces_of(Edge e) const {
    const auto lo = std::lower_bound(edge_faces.begin(), edge_faces.end(), std::make_pair(e, std::make_pair(-1, -1)));
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
      a.edge_faces.push_back({edge_key(m.face_vertices[i], m.face_vertices[next]), {f, i}});
    }
  std::sort(a.edge_faces.begin(), a.edge_faces.end());
  for (const auto& c : m.creases) a.sharpness.push_back({edge_key(c.v0, c.v1), c.sharpness});
  std::sort(a.sharpness.begin(), a.sharpness.end());
  return a;
}

// The slots before and after `slot` in its face.
int prev_slot(const Adjacency& a, int f, int slot) { return slot > a.offsets[f] ? slot - 1 : a.offsets[f + 1] - 1; }
int next_slot(const Adjacency& a, int f, int slot) { return slot + 1 < a.offsets[f + 1] ? slot + 1 : a.offsets[f]; }

struct Fan {
  bool closed = false;
  int faces = 0;
};

// The faces around the vertex at `slot` of face `f` reachable from `f` across edges with exactly
// two faces. Slots, not searches, so that a face of a million vertices costs what its size does.
Fan fan_of(const ControlMesh& m, const Adjacency& a, int f, int slot) {
  Fan fan{false, 1};
  const int v = m.face_vertices[slot];
  int face = f, at = slot, from = m.face_vertices[prev_slot(a, f, slot)];  // leave through the edge after v
  for (int guard = 0; guard < 1 << 20; ++guard) {
    const int before = m.face_vertices[prev_slot(a, face, at)], after = m.face_vertices[next_slot(a, face, at)];
    const int out = before == from ? after : before;
    const auto [lo, hi] = a.faces_of(edge_key(v, out));
    if (hi - lo != 2 || a.edge_faces[lo].second.first == a.edge_faces[lo + 1].second.first) break;  // Bfr: non-manifold
    const auto& other = a.edge_faces[lo].second.first == face ? a.edge_faces[lo + 1].second : a.edge_faces[lo].second;
    if (other.first == f) {
      fan.closed = true;
      return fan;
    }
    face = other.first, from = out, ++fan.faces;
    at = m.face_vertices[other.second] == v ? other.second : next_slot(a, face, other.second);
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

std::vector<char> bfr_defect_faces(const ControlMesh& m) {
  const Adjacency a = adjacency_of(m);
  const std::vector<char> sharp = sharp_vertices(m, a);
  std::vector<char> defect(num_faces(m), 0);
  for (int f = 0; f < num_faces(m); ++f) {
    bool two_face_closed = false, open = false, sharp_corner = false;
    for (int i = a.offsets[f]; i < a.offsets[f + 1]; ++i) {
      const Fan fan = fan_of(m, a, f, i);
      two_face_closed |= fan.closed && fan.faces == 2;
      open |= !fan.closed;
      sharp_corner |= sharp[m.face_vertices[i]] != 0;
    }
    defect[f] = two_face_closed && open && sharp_corner;
  }
  return defect;
}

std::optional<std::string> bfr_overlapping_patch_defect(const ControlMesh& m) {
  const std::vector<char> defect = bfr_defect_faces(m);
  for (int f = 0; f < num_faces(m); ++f) {
    if (defect[f])
      return face_location(m, f) +
             ": OpenSubdiv 3.5.0's Bfr builds this face's patch from uninitialised memory (a corner closed by two "
             "faces beside a boundary and a sharp edge; fixed in OpenSubdiv 3.5.1)";
  }
  return std::nullopt;
}

}  // namespace sdb
