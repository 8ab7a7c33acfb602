#include "schemes/mipgh/atlas.h"

#include <unordered_map>

#include "harness/core/errors.h"

namespace sdb::mipgh {
namespace {

uint64_t directed(int32_t a, int32_t b) { return (uint64_t(uint32_t(a)) << 32) | uint32_t(b); }

struct Builder {
  const ControlMesh& m;
  FacetKinds kinds;
  DAtlas a;
  std::unordered_map<uint64_t, HalfEdge> by_direction;  // (from, to) -> the side running so

  void facets() {
    const int nf = num_faces(m);
    a.num_vertices = num_vertices(m);
    a.facet_corners.resize(nf);
    a.facet_size.resize(nf);
    a.quads_before.assign(nf + 1, 0);
    a.facet_hole.assign(nf, 0);
    for (int f : m.holes) a.facet_hole[f] = 1;
    by_direction.reserve(size_t(nf) * 4);
    size_t first = 0;
    for (int f = 0; f < nf; ++f) {
      const int size = m.face_sizes[f];
      const bool ok = (size == 4 && kinds != FacetKinds::Triangles) || (size == 3 && kinds != FacetKinds::Quads);
      if (!ok)
        throw InputError(face_location(m, f), std::string("MiPGH's atlas here takes ") +
                                                  (kinds == FacetKinds::Quads       ? "quads"
                                                   : kinds == FacetKinds::Triangles ? "triangles"
                                                                                    : "quads and triangles") +
                                                  " only (R1), this face has " + std::to_string(size) + " vertices");
      a.facet_size[f] = static_cast<uint8_t>(size);
      a.quads_before[f + 1] = a.quads_before[f] + (size == 4);
      for (int k = 0; k < size; ++k) a.facet_corners[f][k] = m.face_vertices[first + k];
      first += size;
      for (int k = 0; k < size; ++k) {
        const int32_t from = a.facet_corners[f][k], to = a.facet_corners[f][a.next(f, k)];
        if (from == to) throw InputError(face_location(m, f), "a quad with a repeated vertex");
        if (!by_direction.emplace(directed(from, to), HalfEdge{f, k}).second)
          throw InputError(face_location(m, f), "edge " + std::to_string(from) + "-" + std::to_string(to) +
                                                    " is used twice in one direction (non-manifold or mis-oriented)");
      }
    }
  }

  void edges() {
    const int nf = a.num_facets();
    a.facet_edges.resize(nf);
    a.facet_side_minor.resize(nf);
    for (int f = 0; f < nf; ++f)
      for (int k = 0; k < a.facet_size[f]; ++k) {
        const int32_t from = a.facet_corners[f][k], to = a.facet_corners[f][a.next(f, k)];
        auto twin = by_direction.find(directed(to, from));
        if (twin != by_direction.end() && twin->second.facet < f) continue;  // made from the twin
        const int32_t e = static_cast<int32_t>(a.edges.size());
        DEdge d;
        d.major = {f, k};
        a.facet_edges[f][k] = e, a.facet_side_minor[f][k] = 0;
        if (twin != by_direction.end() && !(twin->second.facet == f)) {
          d.minor = twin->second;
          a.facet_edges[d.minor.facet][d.minor.side] = e, a.facet_side_minor[d.minor.facet][d.minor.side] = 1;
        } else if (twin != by_direction.end()) {
          throw InputError(face_location(m, f), "a quad meets itself along an edge");
        }
        a.edges.push_back(d);
      }
  }

  // Counter-clockwise around v: from (f, corner k) across f's incoming side (corner k-1 -> k) to
  // the facet whose outgoing side is its twin.
  void rings() {
    const int nv = a.num_vertices, nf = a.num_facets();
    std::vector<int32_t> incidences(nv + 1, 0);
    std::vector<HalfEdge> first(nv), boundary_start(nv);
    for (int f = 0; f < nf; ++f)
      for (int k = 0; k < a.facet_size[f]; ++k) {
        const int32_t v = a.facet_corners[f][k];
        ++incidences[v];
        if (first[v].null()) first[v] = {f, k};
        const int32_t next = a.facet_corners[f][a.next(f, k)];
        if (!by_direction.count(directed(next, v))) boundary_start[v] = {f, k};
      }
    a.ring_offsets.assign(nv + 1, 0);
    a.vertex_boundary.assign(nv, 0);
    a.vertex_fans.assign(nv, 1);
    for (int v = 0; v < nv; ++v) {
      a.ring_offsets[v] = static_cast<int32_t>(a.ring.size());
      if (first[v].null()) continue;  // a vertex in no face: it has no node at any level past 0
      const bool boundary = !boundary_start[v].null();
      a.vertex_boundary[v] = boundary;
      HalfEdge at = boundary ? boundary_start[v] : first[v];
      const HalfEdge start = at;
      for (int count = 0;; ++count) {
        if (count == incidences[v]) throw nonmanifold(v);
        a.ring.push_back(at);
        const int32_t prev = a.facet_corners[at.facet][a.prev(at.facet, at.side)];
        auto across = by_direction.find(directed(v, prev));
        if (across == by_direction.end()) break;  // the other boundary edge
        at = {across->second.facet, across->second.side};
        if (at.facet == start.facet && at.side == start.side) break;
      }
      const size_t fan = a.ring.size() - a.ring_offsets[v];
      if (fan != size_t(incidences[v])) a.vertex_fans[v] = 2;  // at least: the ring is the first
    }
    a.ring_offsets[nv] = static_cast<int32_t>(a.ring.size());
  }

  InputError nonmanifold(int v) const {
    return InputError(m.source, "vertex " + std::to_string(v) +
                                    " is not a manifold vertex (its faces do not form one fan)");
  }
};

}  // namespace

DAtlas build_atlas(const ControlMesh& mesh, FacetKinds kinds) {
  Builder b{mesh, kinds, {}, {}};
  b.facets();
  b.edges();
  b.rings();
  return std::move(b.a);
}

}  // namespace sdb::mipgh
