#include "schemes/mipgh/primitives.h"

#include <algorithm>
#include <cstdlib>

namespace sdb::mipgh {

namespace {

// Calls f(offset, i, j) for every node of a D-facet's array at level n: row-major (i, j).
template <class F>
void for_each_node(int size, int n, F&& f) {
  for (int i = 0; i < n; ++i)
    for (int j = 0; size == 4 ? j < n : i + j < n; ++j) f(size == 4 ? i * n + j : tri_offset(n, i, j), i, j);
}

}  // namespace

void compile_primitives(const DAtlas& atlas, const DLoD& lod, int depth, Tessellation& out) {
  const LevelLayout& l = lod.layout(depth);
  const int n = l.n;
  const float step = 1.0f / float(n - 1);
  out.coords.assign(l.num_nodes, SurfaceCoord{});
  // Each node's coord in the D-facet that owns it: interior nodes their own, D-edge nodes the
  // major halfedge's, D-vertices the first of their ring's.
  auto own = [&](int f, RowColumn p) {
    const uint32_t node = lod.facet(depth, f)[facet_offset(atlas.facet_size[f], n, p)];
    out.coords[node] = {uint32_t(f), float(p.j) * step, float(p.i) * step};
  };
  for (int f = 0; f < atlas.num_facets(); ++f)
    for_each_node(atlas.facet_size[f], n, [&](int o, int i, int j) {
      if (lod.facet(depth, f)[o] >= l.facet_base) own(f, {i, j});
    });
  for (const DEdge& e : atlas.edges)
    for (int a = 1; a <= l.s; ++a) own(e.major.facet, side_ij(atlas.facet_size[e.major.facet], e.major.side, n, a, 0));
  for (int v = 0; v < atlas.num_vertices; ++v)
    if (atlas.valence(v) > 0) {
      const HalfEdge& h = atlas.ring[atlas.ring_offsets[v]];
      own(h.facet, side_ij(atlas.facet_size[h.facet], h.side, n, 0, 0));
    }
  out.triangles.clear();
  out.triangles.reserve(size_t(atlas.num_facets()) * 6 * (n - 1) * (n - 1));
  for (int f = 0; f < atlas.num_facets(); ++f) {
    if (atlas.facet_hole[f]) continue;
    const uint32_t* idx = lod.facet(depth, f);
    if (atlas.facet_size[f] == 4) {
      for (int i = 0; i + 1 < n; ++i)
        for (int j = 0; j + 1 < n; ++j) {
          const uint32_t a = idx[i * n + j], b = idx[i * n + j + 1], c = idx[(i + 1) * n + j + 1],
                         d = idx[(i + 1) * n + j];
          out.triangles.insert(out.triangles.end(), {a, b, c, a, c, d});
        }
      continue;
    }
    for (int i = 0; i + 1 < n; ++i)
      for (int j = 0; i + j + 1 < n; ++j) {
        const uint32_t a = idx[tri_offset(n, i, j)], b = idx[tri_offset(n, i, j + 1)], d = idx[tri_offset(n, i + 1, j)];
        out.triangles.insert(out.triangles.end(), {a, b, d});
        if (i + j + 2 < n) out.triangles.insert(out.triangles.end(), {b, idx[tri_offset(n, i + 1, j + 1)], d});
      }
  }
}

namespace {

// Where grid point (i, j) of a D-facet's array lies along side k (a, from corner k), or -1 off it.
int along(int size, int n, int k, RowColumn p) {
  if (size == 4) switch (k) {
      case 0: return p.i == 0 ? p.j : -1;
      case 1: return p.j == n - 1 ? p.i : -1;
      case 2: return p.i == n - 1 ? n - 1 - p.j : -1;
      default: return p.j == 0 ? n - 1 - p.i : -1;
    }
  switch (k) {
    case 0: return p.i == 0 ? p.j : -1;
    case 1: return p.i + p.j == n - 1 ? p.i : -1;
    default: return p.j == 0 ? n - 1 - p.i : -1;
  }
}

// One D-facet's primitives at its drawn level, against the output's numbering.
class AdaptiveFacet {
 public:
  AdaptiveFacet(const DAtlas& atlas, int f, int level, const std::vector<int>& edge_level,
                const std::vector<uint32_t>& edge_out, uint32_t interior_out)
      : atlas_(atlas), f_(f), size_(atlas.facet_size[f]), n_((1 << level) + 1), level_(level),
        edge_level_(edge_level), edge_out_(edge_out), interior_out_(interior_out) {}

  uint32_t id(RowColumn p) const {
    for (int k = 0; k < size_; ++k) {
      const int a = along(size_, n_, k, p);
      if (a == 0) return uint32_t(atlas_.facet_corners[f_][k]);
      if (a > 0 && a < n_ - 1) return edge_id(k, a << (edge_level_[atlas_.facet_edges[f_][k]] - level_));
    }
    const int s = n_ - 2;
    return interior_out_ + uint32_t(size_ == 4 ? (p.i - 1) * s + (p.j - 1) : (p.i - 1) * s - (p.i - 1) * p.i / 2 + (p.j - 1));
  }

  // The triangle (p, q, r), counter-clockwise, split where a side's D-edge is drawn finer.
  void emit(RowColumn p, RowColumn q, RowColumn r, std::vector<uint32_t>& triangles) const {
    const uint32_t v[3] = {id(p), id(q), id(r)};
    const RowColumn g[3] = {p, q, r};
    std::vector<uint32_t> extra[3];
    for (int k = 0; k < 3; ++k) extra[k] = finer(g[k], g[(k + 1) % 3]);
    fan(v, extra, triangles);
  }

 private:
  // The output node at fine coordinate c (from corner k) of side k's D-edge.
  uint32_t edge_id(int k, int c) const {
    const int e = atlas_.facet_edges[f_][k], last = 1 << edge_level_[e];
    const int p = atlas_.facet_side_minor[f_][k] ? last - c : c;
    return edge_out_[e] + uint32_t(p - 1);
  }
  // The nodes a finer D-facet has strictly between grid points p and q, from p to q; none where
  // p q is not a micro-edge of a side.
  std::vector<uint32_t> finer(RowColumn p, RowColumn q) const {
    std::vector<uint32_t> ids;
    for (int k = 0; k < size_; ++k) {
      const int a = along(size_, n_, k, p), b = along(size_, n_, k, q);
      if (a < 0 || b < 0 || std::abs(a - b) != 1) continue;
      const int shift = edge_level_[atlas_.facet_edges[f_][k]] - level_, m = 1 << shift;
      for (int t = 1; t < m; ++t) ids.push_back(edge_id(k, (a << shift) + (b > a ? t : -t)));
      break;
    }
    return ids;
  }
  // Fans the first split edge's nodes from the opposite corner, then splits what is left.
  static void fan(const uint32_t v[3], std::vector<uint32_t> extra[3], std::vector<uint32_t>& out) {
    int k = 0;
    while (k < 3 && extra[k].empty()) ++k;
    if (k == 3) {
      out.insert(out.end(), {v[0], v[1], v[2]});
      return;
    }
    const uint32_t a = v[k], b = v[(k + 1) % 3], c = v[(k + 2) % 3];
    std::vector<uint32_t> chain{a};
    chain.insert(chain.end(), extra[k].begin(), extra[k].end());
    chain.push_back(b);
    for (size_t i = 0; i + 1 < chain.size(); ++i) {
      const uint32_t w[3] = {chain[i], chain[i + 1], c};
      std::vector<uint32_t> sub[3];
      if (i + 2 == chain.size()) sub[1] = extra[(k + 1) % 3];  // b -> c
      if (i == 0) sub[2] = extra[(k + 2) % 3];                 // c -> a
      fan(w, sub, out);
    }
  }

  const DAtlas& atlas_;
  int f_, size_, n_, level_;
  const std::vector<int>& edge_level_;
  const std::vector<uint32_t>& edge_out_;
  uint32_t interior_out_;
};

int interior_count(int size, int level) {
  const int s = (1 << level) - 1;
  return size == 4 ? s * s : s * (s - 1) / 2;
}

}  // namespace

std::vector<uint8_t> vertex_homes(const DAtlas& atlas, const std::vector<uint8_t>& render,
                                  const std::vector<uint8_t>& home) {
  std::vector<uint8_t> level(atlas.num_vertices, 0);
  for (int f = 0; f < atlas.num_facets(); ++f)
    for (int k = 0; k < atlas.facet_size[f]; ++k) {
      uint8_t& l = level[atlas.facet_corners[f][k]];
      l = std::max(l, render[f]);
    }
  for (uint8_t& l : level) l = home[l];
  return level;
}

AdaptiveOutput compile_adaptive(const DAtlas& atlas, const DLoD& lod, const std::vector<uint8_t>& render,
                                const std::vector<uint8_t>& home_of, Tessellation& out) {
  const int V = atlas.num_vertices, E = atlas.num_edges(), F = atlas.num_facets();
  AdaptiveOutput r;
  r.homes.resize(lod.depth() + 1), r.nodes.resize(lod.depth() + 1);
  std::vector<int> edge_level(E);
  for (int e = 0; e < E; ++e) {
    const DEdge& d = atlas.edges[e];
    edge_level[e] = std::max<int>(render[d.major.facet], d.minor.null() ? 0 : render[d.minor.facet]);
  }
  const std::vector<uint8_t> vertex_home = vertex_homes(atlas, render, home_of);
  uint32_t next = uint32_t(V);
  std::vector<uint32_t> edge_out(E), facet_out(F);
  for (int e = 0; e < E; ++e) edge_out[e] = next, next += (1u << edge_level[e]) - 1;
  for (int f = 0; f < F; ++f) facet_out[f] = next, next += uint32_t(interior_count(atlas.facet_size[f], render[f]));
  out.coords.assign(next, SurfaceCoord{});
  auto coord = [&](int f, int level, RowColumn p) {
    const float step = 1.0f / float(1 << level);
    return SurfaceCoord{uint32_t(f), float(p.j) * step, float(p.i) * step};
  };
  for (int v = 0; v < V; ++v) {
    const int home = vertex_home[v];
    r.homes[home].vertices.push_back(v), r.nodes[home].push_back({uint32_t(v), uint32_t(v)});
    if (atlas.valence(v) == 0) continue;
    const HalfEdge& h = atlas.ring[atlas.ring_offsets[v]];
    out.coords[v] = coord(h.facet, 0, side_ij(atlas.facet_size[h.facet], h.side, 2, 0, 0));
  }
  for (int e = 0; e < E; ++e) {
    const int level = edge_level[e], home = home_of[level], shift = home - level;
    if (level == 0) continue;
    r.homes[home].edges.push_back(e);
    const HalfEdge& h = atlas.edges[e].major;
    for (int p = 1; p < (1 << level); ++p) {
      const uint32_t o = edge_out[e] + uint32_t(p - 1);
      r.nodes[home].push_back({lod.layout(home).edge_node(e, (p << shift) - 1), o});
      out.coords[o] = coord(h.facet, level, side_ij(atlas.facet_size[h.facet], h.side, (1 << level) + 1, p, 0));
    }
  }
  for (int f = 0; f < F; ++f) {
    const int level = render[f], home = home_of[level], shift = home - level, size = atlas.facet_size[f];
    const int n = (1 << level) + 1, s = n - 2, nh = lod.layout(home).n;
    if (interior_count(size, level) == 0) continue;
    r.homes[home].facets.push_back(f);
    uint32_t o = facet_out[f];
    for (int i = 1; i <= s; ++i)
      for (int j = 1; size == 4 ? j <= s : i + j <= s; ++j, ++o) {
        r.nodes[home].push_back({lod.facet(home, f)[facet_offset(size, nh, {i << shift, j << shift})], o});
        out.coords[o] = coord(f, level, {i, j});
      }
  }
  out.triangles.clear();
  for (int f = 0; f < F; ++f) {
    if (atlas.facet_hole[f]) continue;
    const AdaptiveFacet facet(atlas, f, render[f], edge_level, edge_out, facet_out[f]);
    const int n = (1 << render[f]) + 1;
    if (atlas.facet_size[f] == 4) {
      for (int i = 0; i + 1 < n; ++i)
        for (int j = 0; j + 1 < n; ++j) {
          facet.emit({i, j}, {i, j + 1}, {i + 1, j + 1}, out.triangles);
          facet.emit({i, j}, {i + 1, j + 1}, {i + 1, j}, out.triangles);
        }
      continue;
    }
    for (int i = 0; i + 1 < n; ++i)
      for (int j = 0; i + j + 1 < n; ++j) {
        facet.emit({i, j}, {i, j + 1}, {i + 1, j}, out.triangles);
        if (i + j + 2 < n) facet.emit({i, j + 1}, {i + 1, j + 1}, {i + 1, j}, out.triangles);
      }
  }
  return r;
}

std::vector<uint32_t> same_points_at(const DAtlas& atlas, const DLoD& lod, int sigma, int inner) {
  const int n = lod.layout(sigma).n, m = lod.layout(inner).n, shift = inner - sigma;
  std::vector<uint32_t> to(lod.layout(sigma).num_nodes);
  for (int v = 0; v < atlas.num_vertices; ++v) to[v] = v;  // D-vertices (bare ones included) keep their slot
  for (int f = 0; f < atlas.num_facets(); ++f) {
    const int size = atlas.facet_size[f];
    const uint32_t *coarse = lod.facet(sigma, f), *fine = lod.facet(inner, f);
    for_each_node(size, n, [&](int o, int i, int j) {
      const int fi = i << shift, fj = j << shift;
      to[coarse[o]] = fine[size == 4 ? fi * m + fj : tri_offset(m, fi, fj)];
    });
  }
  return to;
}

}  // namespace sdb::mipgh
