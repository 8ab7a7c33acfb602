#include "schemes/mipgh/primitives.h"

#include <algorithm>

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
