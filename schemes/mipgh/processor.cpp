#include "schemes/mipgh/processor.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "schemes/mipgh/facet_masks.h"
#include "schemes/mipgh/regular_patches.h"
#include "schemes/mipgh/tile.h"

namespace sdb::mipgh {
namespace {

template <class F>
void for_each(int count, bool parallel, int grain, F&& f) {
  if (!parallel) {
    for (int i = 0; i < count; ++i) f(i);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<int>(0, count, grain), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(); i != r.end(); ++i) f(i);
  });
}

// The nodes along a D-edge and the rows next to it in its two D-facets, read once per visit:
// a[t] on the edge, b[t] one in from the major side, c[t] one in from the minor side (t counted
// from the major halfedge's first corner).
struct Strip {
  std::vector<V3> a, b, c;
  bool quad_major = true, quad_minor = true;
};

// x, y, z in the lanes of one SSE register: a stencil's sum is one operation for the three
// coordinates, each lane the same float operations as the scalar sum.
using Xyz = float __attribute__((vector_size(16)));
inline Xyz widen(const V3& p) { return Xyz{p.x, p.y, p.z, 0.0f}; }
inline V3 narrow(Xyz v) { return {v[0], v[1], v[2]}; }

// A tag-free D-edge's next nodes from its strip (edge points at even k, vertex points at odd k of
// out), in node order; each strip node is widened once, the window of three columns rolled along.
void strip_stencils(const V3* A, const V3* B, const V3* C, int n, bool quad, V3* out) {
  Xyz a0 = widen(A[0]), a1 = widen(A[1]), b0 = widen(B[0]), c0 = widen(C[0]);
  if (quad) {  // Figure 20
    Xyz b1 = widen(B[1]), c1 = widen(C[1]);
    out[0] = narrow(edge_vertex(a0, a1, b0, b1, c0, c1));
    for (int t = 1; t + 1 < n; ++t) {
      const Xyz a2 = widen(A[t + 1]), b2 = widen(B[t + 1]), c2 = widen(C[t + 1]);
      out[2 * t - 1] = narrow(vertex_vertex4(a1, a2, b1, a0, c1, b2, b0, c0, c2));
      out[2 * t] = narrow(edge_vertex(a1, a2, b1, b2, c1, c2));
      a0 = a1, a1 = a2, b0 = b1, b1 = b2, c0 = c1, c1 = c2;
    }
    return;
  }
  out[0] = narrow(loop_edge_vertex(a0, a1, b0, c0));  // Loop
  for (int t = 1; t + 1 < n; ++t) {
    const Xyz a2 = widen(A[t + 1]), b1 = widen(B[t]), c1 = widen(C[t]);
    out[2 * t - 1] = narrow(loop_vertex6(a1, a2, b1, b0, a0, c0, c1));
    out[2 * t] = narrow(loop_edge_vertex(a1, a2, b1, c1));
    a0 = a1, a1 = a2, b0 = b1, c0 = c1;
  }
}

// `needed` squares rounded up to whole SIMD vectors of eight, within the `room` the tile has: a
// loop's scalar remainder costs more than the squares it computes for nothing (at n = 3, 6 squares
// left scalar took more instructions than 9 in one vector and one remainder).
int whole_lanes(int needed, int room) { return std::min((needed + 7) & ~7, room); }

thread_local tile::Tile t_tile, t_strip_rows;
thread_local Strip t_strip;
thread_local tile::Planes t_planes, t_strip_planes;
thread_local VertexDisk t_disk;

}  // namespace

bool MeshProcessor::load_tile(int sigma, TileFacets facets, const V3* src) const {
  const LevelLayout& l = lod_.layout(sigma);
  const int n = l.n;
  const bool quad = atlas_.facet_size[facets.first] == 4;
  if (quad) {
    t_tile.load_quad(lod_.facet(sigma, facets.first), src + l.interior(facets.first), n, src);
  } else {
    t_tile.load_triangle(lod_.facet(sigma, facets.first), src + l.interior(facets.first), n, src, false);
    if (facets.second >= 0) t_tile.load_triangle(lod_.facet(sigma, facets.second), src + l.interior(facets.second), n, src, true);
  }
  t_planes.fit(size_t(t_tile.squares()));
  return quad;
}

void MeshProcessor::visit_facets(int sigma, TileFacets facets, const V3* src, V3* dst) const {
  const int n = lod_.layout(sigma).n, width = lod_.layout(sigma + 1).s;  // target rows, columns 1 .. width
  const bool quad = load_tile(sigma, facets, src);
  const tile::Tile& t = t_tile;
  tile::Planes& s = t_planes;
  const int w = t.stride;
  // every target lies at a square of rows 0 .. n - 2 (tile.h), the first triangle's and the turned one's
  const int count = whole_lanes((n - 1) * w, t.squares());
  for (int k = 0; k < 3; ++k)
    (quad ? tile::quad_classes : tile::triangle_classes)(t.plane(k), w, count, s.v[0][k].data(), s.v[1][k].data(),
                                                         s.v[2][k].data(), s.v[3][k].data());
  const LevelLayout& next = lod_.layout(sigma + 1);
  tile::assemble_targets(s, n, w, width, quad, false, dst + next.interior(facets.first));
  if (facets.second >= 0) tile::assemble_targets(s, n, w, width, quad, true, dst + next.interior(facets.second));
}

void MeshProcessor::visit_facet_corners(int sigma, int f, const V3* src, V3* dst) const {
  const int n = lod_.layout(sigma).n, width = lod_.layout(sigma + 1).s;
  const uint32_t* idx = lod_.facet(sigma, f);  // a quad's n x n nodes, row-major
  V3* out = dst + lod_.layout(sigma + 1).interior(f);
  // The facet point of square (a, b), as quad_classes computes it
  auto facet_point = [&](int a, int b) {
    const V3 p = src[idx[a * n + b]], q = src[idx[(a + 1) * n + b + 1]], r = src[idx[a * n + b + 1]],
             u = src[idx[(a + 1) * n + b]];
    return V3{0.25f * ((p.x + q.x) + (r.x + u.x)), 0.25f * ((p.y + q.y) + (r.y + u.y)), 0.25f * ((p.z + q.z) + (r.z + u.z))};
  };
  out[0] = facet_point(0, 0), out[width - 1] = facet_point(0, n - 2);
  out[size_t(width - 1) * size_t(width)] = facet_point(n - 2, 0), out[size_t(width) * size_t(width) - 1] = facet_point(n - 2, n - 2);
}

void MeshProcessor::visit_edge_ends(int sigma, int e, const V3* src, V3* dst) const {
  const int n = lod_.layout(sigma).n;
  const DEdge& d = atlas_.edges[e];
  const uint32_t *f = lod_.facet(sigma, d.major.facet), *g = lod_.facet(sigma, d.minor.facet);
  const int32_t *on = side_rows(sigma, 4, d.major.side, 0), *in = side_rows(sigma, 4, d.major.side, 1);
  const int32_t* across = side_rows(sigma, 4, d.minor.side, 1);
  V3* out = dst + lod_.layout(sigma + 1).edge_node(e, 0);
  // strip_stencils' edge point of micro-edge (t, t + 1): a along the edge, b one in on the
  // major's side, c on the minor's (whose row runs the other way)
  auto edge_point = [&](int t) {
    const auto a = [&](int k) { return widen(src[f[on[k]]]); };
    const auto b = [&](int k) { return widen(src[f[in[k]]]); };
    const auto c = [&](int k) { return widen(src[g[across[n - 1 - k]]]); };
    return narrow(edge_vertex(a(t), a(t + 1), b(t), b(t + 1), c(t), c(t + 1)));
  };
  out[0] = edge_point(0), out[2 * (n - 2)] = edge_point(n - 2);
}

MeshProcessor::MeshProcessor(const DAtlas& atlas, const DLoD& lod, const EdgeTags& tags, const MeshShader& shader)
    : atlas_(atlas), lod_(lod), tags_(tags), shader_(shader), vertex_order_(atlas.num_vertices) {
  // A D-vertex's ring lies in the D-facets around it, far apart in memory at fine levels: visited
  // in the order of their first D-facet they follow the facets' storage instead of jumping.
  auto first = [&](int v) { return atlas.valence(v) ? atlas.ring[atlas.ring_offsets[v]].facet : -1; };
  for (int v = 0; v < atlas.num_vertices; ++v) vertex_order_[v] = v;
  std::stable_sort(vertex_order_.begin(), vertex_order_.end(), [&](int a, int b) { return first(a) < first(b); });
  plan_tiles();
  // Offsets of the rows along each side (depth 0 and 1) in a D-facet's array, every level:
  // a triangle's three sides, then a quad's four.
  for (int sigma = 0; sigma <= lod.depth(); ++sigma) {
    const int n = lod.layout(sigma).n;
    std::vector<int32_t> rows(size_t(7) * 2 * n, 0);
    for (int kind = 0; kind < 7; ++kind)
      for (int depth = 0; depth < 2; ++depth)
        for (int a = 0; a < n; ++a) {
          const int size = kind < 3 ? 3 : 4, side = kind < 3 ? kind : kind - 3;
          if (size == 3 && a + depth >= n) continue;  // a triangle's inner row is one shorter
          rows[(kind * 2 + depth) * n + a] = facet_side_offset(size, side, n, a, depth);
        }
    side_rows_.push_back(std::move(rows));
  }
}

void MeshProcessor::plan_tiles() {
  for (int f = 0; f < atlas_.num_facets(); ++f) {
    const bool pair = atlas_.facet_size[f] == 3 && f + 1 < atlas_.num_facets() && atlas_.facet_size[f + 1] == 3;
    tiles_.push_back({f, pair ? f + 1 : -1});
    f += pair;
  }
  // Each D-edge and D-vertex visited right after the tile of the last D-facet it reads: the other
  // D-facets (neighbours a mesh's face order keeps a few dozen faces apart) were loaded a few
  // tiles before and are still in cache, where a pass of their own would fetch them again from
  // memory, one cache line per node along a side.
  std::vector<int32_t> tile_of(size_t(atlas_.num_facets()), 0);
  for (size_t i = 0; i < tiles_.size(); ++i) {
    tile_of[size_t(tiles_[i].first)] = int32_t(i);
    if (tiles_[i].second >= 0) tile_of[size_t(tiles_[i].second)] = int32_t(i);
  }
  std::vector<int32_t> edge_tile(size_t(atlas_.num_edges())), vertex_tile(size_t(atlas_.num_vertices), 0);
  for (int e = 0; e < atlas_.num_edges(); ++e) {
    const DEdge& d = atlas_.edges[e];
    edge_tile[e] = std::max(tile_of[d.major.facet], d.minor.null() ? 0 : tile_of[d.minor.facet]);
  }
  for (int v = 0; v < atlas_.num_vertices; ++v)
    for (int i = atlas_.ring_offsets[v]; i < atlas_.ring_offsets[v + 1]; ++i)
      vertex_tile[v] = std::max(vertex_tile[v], tile_of[atlas_.ring[i].facet]);
  tile_edges_ = PerTile(edge_tile, tiles_.size());
  tile_vertices_ = PerTile(vertex_tile, tiles_.size());
}

void MeshProcessor::load_strip(int sigma, int e, const V3* src) const {
  const int n = lod_.layout(sigma).n;
  const DEdge& d = atlas_.edges[e];
  Strip& s = t_strip;
  if (s.a.size() < size_t(n)) s.a.resize(n), s.b.resize(n), s.c.resize(n);  // a resize per visit cost a fifth of it
  const int fs = atlas_.facet_size[d.major.facet];
  const uint32_t* f = lod_.facet(sigma, d.major.facet);
  const int32_t* on = side_rows(sigma, fs, d.major.side, 0);
  const int32_t* in = side_rows(sigma, fs, d.major.side, 1);
  // the edge's own nodes lie together in storage (lod.h), from the major's first corner on
  s.a[0] = src[f[on[0]]], s.a[n - 1] = src[f[on[n - 1]]];
  std::copy_n(src + lod_.layout(sigma).edge_node(e, 0), n - 2, s.a.data() + 1);
  // the row one in: n nodes in a quad, n - 1 in a triangle (node t next to a[t] and a[t + 1])
  for (int t = 0; t < n - (fs == 3); ++t) s.b[t] = src[f[in[t]]];
  s.quad_major = fs == 4;
  if (d.minor.null()) return;
  const int gs = atlas_.facet_size[d.minor.facet];
  const uint32_t* g = lod_.facet(sigma, d.minor.facet);
  const int32_t* across = side_rows(sigma, gs, d.minor.side, 1);
  s.quad_minor = gs == 4;
  // c[t] runs the major's way: a quad's node across from a[t]; a triangle's between a[t], a[t + 1]
  const int last = gs == 4 ? n - 1 : n - 2;
  for (int t = 0; t <= last; ++t) s.c[t] = src[g[across[last - t]]];
}

bool MeshProcessor::load_strip_rows(int sigma, int e, const V3* src) const {
  const int n = lod_.layout(sigma).n;
  const DEdge& d = atlas_.edges[e];
  tile::Tile& rows = t_strip_rows;
  rows.shape(3, n);
  t_strip_planes.fit(size_t(n));
  float *x = rows.plane(0), *y = rows.plane(1), *z = rows.plane(2);
  auto put = [&](int L, uint32_t node) {
    const V3& p = src[node];
    x[L] = p.x, y[L] = p.y, z[L] = p.z;
  };
  const int size = atlas_.facet_size[d.major.facet];
  const uint32_t *f = lod_.facet(sigma, d.major.facet), *g = lod_.facet(sigma, d.minor.facet);
  const int32_t *on = side_rows(sigma, size, d.major.side, 0), *in = side_rows(sigma, size, d.major.side, 1);
  const int32_t* across = side_rows(sigma, size, d.minor.side, 1);
  put(n, f[on[0]]), put(2 * n - 1, f[on[n - 1]]);
  tile::split_run(src + lod_.layout(sigma).edge_node(e, 0), n - 2, x + n + 1, y + n + 1, z + n + 1);
  for (int t = 0; t < n - (size == 3); ++t) put(2 * n + t, f[in[t]]);
  // the minor's row runs the other way: its node last - t at column t (+ 1 in a triangle)
  const int last = size == 4 ? n - 1 : n - 2, shift = size == 3;
  for (int t = 0; t <= last; ++t) put(t + shift, g[across[last - t]]);
  return size == 4;
}

const int32_t* MeshProcessor::side_rows(int sigma, int size, int side, int depth) const {
  return side_rows_[sigma].data() + ((size == 4 ? 3 + side : side) * 2 + depth) * lod_.layout(sigma).n;
}

// The 1-disk of the strip's node t, counter-clockwise seen from the major D-facet: along +, the
// major side's inner nodes, along -, the minor side's.
void MeshProcessor::strip_disk(int sigma, int e, int t, VertexDisk& disk) const {
  const Strip& s = t_strip;
  const bool boundary = atlas_.edges[e].minor.null();
  const int major_edges = s.quad_major ? 1 : 2, minor_edges = boundary ? 0 : s.quad_minor ? 1 : 2;
  disk.resize(2 + major_edges + minor_edges, 1 + major_edges + (boundary ? 0 : minor_edges + 1));
  disk.c = s.a[t];
  int k = 0, q = 0;
  disk.e[k++] = s.a[t + 1];
  if (s.quad_major) {
    disk.d[q++] = s.b[t + 1], disk.e[k++] = s.b[t], disk.d[q++] = s.b[t - 1];
  } else {
    disk.d[q++] = s.a[t], disk.e[k++] = s.b[t], disk.d[q++] = s.a[t], disk.e[k++] = s.b[t - 1], disk.d[q++] = s.a[t];
  }
  for (int i = 0; i < q; ++i) disk.face_size[i] = s.quad_major ? 4 : 3;
  const int back = k, major_faces = q;
  disk.e[k++] = s.a[t - 1];
  if (!boundary) {
    if (s.quad_minor) {
      disk.d[q++] = s.c[t - 1], disk.e[k++] = s.c[t], disk.d[q++] = s.c[t + 1];
    } else {
      disk.d[q++] = s.a[t], disk.e[k++] = s.c[t - 1], disk.d[q++] = s.a[t], disk.e[k++] = s.c[t], disk.d[q++] = s.a[t];
    }
  }
  for (int i = major_faces; i < q; ++i) disk.face_size[i] = s.quad_minor ? 4 : 3;
  disk.sharpness = disk.child_sharpness = 0;
  for (int i = 0; i < disk.edges; ++i) disk.edge_sharpness[i] = disk.child_edge_sharpness[i] = 0;
  disk.edge_sharpness[0] = tags_.micro_edge(sigma, e, t);
  disk.edge_sharpness[back] = tags_.micro_edge(sigma, e, t - 1);
  if (sigma < lod_.depth()) {
    disk.child_edge_sharpness[0] = tags_.micro_edge(sigma + 1, e, 2 * t);
    disk.child_edge_sharpness[back] = tags_.micro_edge(sigma + 1, e, 2 * t - 1);
  }
}

bool MeshProcessor::fast_edge(int e) const {
  const DEdge& d = atlas_.edges[e];
  return tags_.slot[e] < 0 && !d.minor.null() && atlas_.facet_size[d.major.facet] == atlas_.facet_size[d.minor.facet];
}

void MeshProcessor::edge_disk(int sigma, int e, int t, EdgeDisk& disk) const {
  const Strip& s = t_strip;
  const bool boundary = atlas_.edges[e].minor.null();
  disk.faces = boundary ? 1 : 2;
  disk.face_size[0] = s.quad_major ? 4 : 3, disk.face_size[1] = s.quad_minor ? 4 : 3;
  disk.v0 = s.a[t], disk.v1 = s.a[t + 1];
  disk.f[0][0] = s.b[t], disk.f[0][1] = s.quad_major ? s.b[t + 1] : s.b[t];
  if (!boundary) disk.f[1][0] = s.c[t], disk.f[1][1] = s.quad_minor ? s.c[t + 1] : s.c[t];
  disk.sharpness = tags_.micro_edge(sigma, e, t);
  disk.child_sharpness[0] = tags_.micro_edge(sigma + 1, e, 2 * t);
  disk.child_sharpness[1] = tags_.micro_edge(sigma + 1, e, 2 * t + 1);
}

void MeshProcessor::visit_edge(int sigma, int e, const V3* src, V3* dst) const {
  const int n = lod_.layout(sigma).n;
  V3* out = dst + lod_.layout(sigma + 1).edge_node(e, 0);
  const bool fast = fast_edge(e);
  if (fast && n < tile::kLongRow) {  // tag-free and short: the stencils node by node
    load_strip(sigma, e, src);
    const Strip& s = t_strip;
    strip_stencils(s.a.data(), s.b.data(), s.c.data(), n, s.quad_major, out);
    return;
  }
  if (fast) {  // tag-free: the tile's stencils (Figure 20's, or Loop's) along row 1
    const bool quad = load_strip_rows(sigma, e, src);
    const tile::Tile& rows = t_strip_rows;
    tile::Planes& s = t_strip_planes;
    for (int k = 0; k < 3; ++k)
      (quad ? tile::quad_classes : tile::triangle_classes)(rows.plane(k) + n, n, n, s.v[0][k].data(), s.v[1][k].data(),
                                                           s.v[2][k].data(), s.v[3][k].data());
    const float *vx = s.v[0][0].data(), *vy = s.v[0][1].data(), *vz = s.v[0][2].data();
    const float *ex = s.v[1][0].data(), *ey = s.v[1][1].data(), *ez = s.v[1][2].data();
    for (int t = 0; t + 1 < n; ++t) out[2 * t] = {ex[t], ey[t], ez[t]};
    for (int t = 1; t + 1 < n; ++t) out[2 * t - 1] = {vx[t], vy[t], vz[t]};
    return;
  }
  load_strip(sigma, e, src);
  EdgeDisk edge;
  for (int t = 0; t + 1 < n; ++t) {
    edge_disk(sigma, e, t, edge);
    out[2 * t] = shader_.edge_vertex(edge);
  }
  VertexDisk& disk = t_disk;
  for (int t = 1; t + 1 < n; ++t) {
    strip_disk(sigma, e, t, disk);
    out[2 * t - 1] = shader_.vertex_vertex(disk);
  }
}

void MeshProcessor::gather_vertex(int sigma, int v, const V3* src, VertexDisk& disk,
                                  std::vector<float>* far_half) const {
  const int n = lod_.layout(sigma).n;
  const int begin = atlas_.ring_offsets[v], faces = atlas_.ring_offsets[v + 1] - begin;
  const bool boundary = atlas_.vertex_boundary[v];
  disk.resize(faces + boundary, faces);
  disk.sided = true;
  // No positions (src null): the disk's tags alone, for vertex_tangents.cpp.
  const V3 none{0, 0, 0};
  auto at = [&](uint32_t node) { return src ? src[node] : none; };
  disk.c = at(v);
  const int last = (1 << sigma) - 1;
  const bool child = sigma < lod_.depth() && tags_.any;
  // The micro-edge of the side next to v: index 0 from the major halfedge's start.
  // far: the one after it (at sigma + 1, the other half of the level-sigma micro-edge).
  auto sharpness = [&](int level, int facet, int side, bool v_at_start, bool far = false) {
    const int e = atlas_.facet_edges[facet][side];
    const bool at_major_start = v_at_start != bool(atlas_.facet_side_minor[facet][side]);
    const int end = level == sigma ? last : 2 * last + 1;
    return tags_.micro_edge(level, e, at_major_start ? int(far) : end - int(far));
  };
  for (int i = 0; i < faces; ++i) {
    const HalfEdge& h = atlas_.ring[begin + i];
    const uint32_t* idx = lod_.facet(sigma, h.facet);
    const int size = atlas_.facet_size[h.facet];
    disk.e[i] = at(idx[side_rows(sigma, size, h.side, 0)[1]]);
    // a quad's corner across from v (a triangle has none: Loop's masks weigh no faces)
    disk.d[i] = size == 4 ? at(idx[side_rows(sigma, 4, h.side, 1)[1]]) : disk.c;
    disk.face_size[i] = uint8_t(size);
  }
  if (!tags_.any) {
    std::fill_n(disk.edge_sharpness.begin(), faces, 0.0f);
    std::fill_n(disk.child_edge_sharpness.begin(), faces, 0.0f);
  } else {
    for (int i = 0; i < faces; ++i) {
      const HalfEdge& h = atlas_.ring[begin + i];
      disk.edge_sharpness[i] = sharpness(sigma, h.facet, h.side, true);
      disk.child_edge_sharpness[i] = child ? sharpness(sigma + 1, h.facet, h.side, true) : 0.0f;
    }
  }
  if (boundary) {
    const HalfEdge& h = atlas_.ring[begin + faces - 1];
    const int size = atlas_.facet_size[h.facet], side = atlas_.prev(h.facet, h.side);
    disk.e[faces] = at(lod_.facet(sigma, h.facet)[facet_side_offset(size, side, n, n - 2, 0)]);
    disk.edge_sharpness[faces] = tags_.any ? sharpness(sigma, h.facet, side, false) : 0.0f;
    disk.child_edge_sharpness[faces] = child ? sharpness(sigma + 1, h.facet, side, false) : 0.0f;
  }
  if (far_half) {
    far_half->assign(disk.edges, 0.0f);
    for (int i = 0; child && i < disk.edges; ++i) {
      const HalfEdge& h = atlas_.ring[begin + std::min(i, faces - 1)];
      if (i < faces) (*far_half)[i] = sharpness(sigma + 1, h.facet, h.side, true, true);
      else (*far_half)[i] = sharpness(sigma + 1, h.facet, atlas_.prev(h.facet, h.side), false, true);
    }
  }
  disk.sharpness = tags_.any ? tags_.vertex[sigma][v] : 0.0f;
  disk.child_sharpness = child ? tags_.vertex[sigma + 1][v] : 0.0f;
}

void MeshProcessor::visit_vertex(int sigma, int v, const V3* src, V3* dst) const {
  if (atlas_.valence(v) == 0 || atlas_.vertex_fans[v] > 1) {  // in no face, or a corner of several fans
    dst[v] = src[v];
    return;
  }
  VertexDisk& disk = t_disk;
  gather_vertex(sigma, v, src, disk);
  dst[v] = shader_.vertex_vertex(disk);
}

void MeshProcessor::step(int sigma, const V3* src, V3* dst, bool parallel, const RegularPatches* patches) const {
  if (lod_.adaptive()) return step_adaptive(sigma, src, dst, parallel);
  if (!patches || patches->patch.empty()) {  // every node (and no test per visit: Loop has no patches)
    for_each(int(tiles_.size()), parallel, 32, [&](int i) {
      visit_facets(sigma, tiles_[i], src, dst);
      for (int32_t e : tile_edges_.of(i)) visit_edge(sigma, e, src, dst);
      for (int32_t v : tile_vertices_.of(i)) visit_vertex(sigma, v, src, dst);
    });
    return;
  }
  auto regular = [&](int f) { return f >= 0 && patches->regular(f); };
  for_each(int(tiles_.size()), parallel, 32, [&](int i) {
    if (regular(tiles_[i].first)) visit_facet_corners(sigma, tiles_[i].first, src, dst);
    else visit_facets(sigma, tiles_[i], src, dst);
    for (int32_t e : tile_edges_.of(i)) {
      const DEdge& d = atlas_.edges[e];
      if (regular(d.major.facet) && regular(d.minor.facet) && fast_edge(e)) visit_edge_ends(sigma, e, src, dst);
      else visit_edge(sigma, e, src, dst);
    }
    for (int32_t v : tile_vertices_.of(i)) visit_vertex(sigma, v, src, dst);
  });
}

bool MeshProcessor::edge_readable(int sigma, int e) const {
  const DEdge& d = atlas_.edges[e];
  return lod_.holds_facet(sigma, d.major.facet) && (d.minor.null() || lod_.holds_facet(sigma, d.minor.facet));
}

bool MeshProcessor::vertex_readable(int sigma, int v) const {
  for (int i = atlas_.ring_offsets[v]; i < atlas_.ring_offsets[v + 1]; ++i)
    if (!lod_.holds_facet(sigma, atlas_.ring[i].facet)) return false;
  return true;
}

template <class F>
void MeshProcessor::copied_edge_nodes(int sigma, int e, F&& node) const {
  const LevelLayout &l = lod_.layout(sigma), &next = lod_.layout(sigma + 1);
  const HalfEdge& h = atlas_.edges[e].major;
  const uint32_t first = uint32_t(atlas_.facet_corners[h.facet][h.side]);
  const uint32_t last = uint32_t(atlas_.facet_corners[h.facet][atlas_.next(h.facet, h.side)]);
  auto a = [&](int t) { return t == 0 ? first : t == l.n - 1 ? last : l.edge_node(e, t - 1); };
  for (int t = 0; t + 1 < l.n; ++t) {
    node(next.edge_node(e, 2 * t), a(t), a(t + 1));
    if (t > 0) node(next.edge_node(e, 2 * t - 1), a(t), a(t));
  }
}

void MeshProcessor::copy_edge(int sigma, int e, const V3* src, V3* dst) const {
  copied_edge_nodes(sigma, e, [&](uint32_t target, uint32_t i, uint32_t j) {
    const V3 p = src[i], q = src[j];
    dst[target] = i == j ? p : V3{0.5f * (p.x + q.x), 0.5f * (p.y + q.y), 0.5f * (p.z + q.z)};
  });
}

void MeshProcessor::step_adaptive(int sigma, const V3* src, V3* dst, bool parallel) const {
  const std::vector<int32_t>&facets = lod_.facets_held(sigma + 1), &edges = lod_.edges_held(sigma + 1);
  for_each(int(facets.size()), parallel, 64, [&](int i) { visit_facets(sigma, {facets[i], -1}, src, dst); });
  for_each(int(edges.size()), parallel, 256, [&](int i) {
    const int e = edges[i];
    if (edge_readable(sigma, e)) visit_edge(sigma, e, src, dst);
    else copy_edge(sigma, e, src, dst);
  });
  for_each(atlas_.num_vertices, parallel, 512, [&](int i) {
    const int v = vertex_order_[i];
    if (vertex_readable(sigma, v)) visit_vertex(sigma, v, src, dst);
    else dst[v] = src[v];
  });
}

namespace {

// A limit position, moved by the offset where there is one.
inline V3 placed(float x, float y, float z, const V3* offset) {
  return offset ? V3{x + offset->x, y + offset->y, z + offset->z} : V3{x, y, z};
}

}  // namespace

void MeshProcessor::project_facets(int sigma, TileFacets facets, const V3* src, V3* position, V3* normal,
                                   const V3* offset, const BaseLevel* base) const {
  const LevelLayout& l = lod_.layout(sigma);
  const int n = l.n;
  // A regular D-facet's interior from its patch on level 0 (regular_patches.h), positions and
  // normals into the planes in the level's order, then moved to the output as one run: its
  // level-sigma nodes are not gathered at all.
  if (n >= 3 && base && base->patches && base->patches->regular(facets.first)) {
    tile::Planes& s = t_planes;
    s.fit(size_t(n) * size_t(n));
    base->patches->interior_limit(facets.first, sigma, base->points, base->origin, s.v[0][0].data(), s.v[0][1].data(),
                                  s.v[0][2].data(), s.normal[0].data(), s.normal[1].data(), s.normal[2].data());
    tile::assemble_limit_run(s, l.s * l.s, offset, position + l.interior(facets.first), normal + l.interior(facets.first));
    return;
  }
  const bool quad = load_tile(sigma, facets, src);
  const tile::Tile& t = t_tile;
  tile::Planes& s = t_planes;
  const int w = t.stride;
  // the interior nodes lie in rows 1 .. n - 2 (tile.h), the first triangle's and the turned one's
  const int first = w, count = whole_lanes((n - 2) * w, t.squares() - first);
  auto at = [&](std::vector<float>& plane) { return plane.data() + first; };
  // The other untagged interior quads' normals from their 1-ring's composed masks (facet_masks.h),
  // written over the normals after assembly (the planes' normals are then whatever the last tile
  // left, never read); the stencils give their positions.
  const bool masked = n >= 3 && base && base->masks && base->masks->has(facets.first);
  if (masked) {
    tile::quad_limit_positions(t.plane(0) + first, t.plane(1) + first, t.plane(2) + first, w, count, at(s.v[0][0]),
                               at(s.v[0][1]), at(s.v[0][2]));
  } else {
    (quad ? tile::quad_limit_normals : tile::triangle_limit_normals)(
        t.plane(0) + first, t.plane(1) + first, t.plane(2) + first, w, count, at(s.v[0][0]), at(s.v[0][1]),
        at(s.v[0][2]), at(s.normal[0]), at(s.normal[1]), at(s.normal[2]));
  }
  auto assemble = [&](int f, bool turned) {
    tile::assemble_limit(s, n, w, l.s, quad, turned, offset, position + l.interior(f), normal + l.interior(f));
    if (masked) base->masks->interior_normals(f, sigma, base->points, normal + l.interior(f));
  };
  assemble(facets.first, false);
  if (facets.second >= 0) assemble(facets.second, true);
}

void MeshProcessor::project_edge(int sigma, int e, const V3* src, V3* position, V3* normal, const V3* offset,
                                 const BaseLevel* base) const {
  // A D-edge of a regular D-facet, its positions and normals from the facet's patch (the major's,
  // else the minor's, whose side runs the other way): its strip is not gathered at all.
  const LevelLayout& l = lod_.layout(sigma);
  const DEdge& d = atlas_.edges[e];
  const bool patched = base && base->patches && l.s > 0;
  if (patched && (base->patches->regular(d.major.facet) || (!d.minor.null() && base->patches->regular(d.minor.facet)))) {
    const bool from_major = base->patches->regular(d.major.facet);
    const HalfEdge& h = from_major ? d.major : d.minor;
    V3 *p = position + l.edge_node(e, 0), *q = normal + l.edge_node(e, 0);
    base->patches->side_limit(h.facet, sigma, h.side, base->points, base->origin, offset, p, q);
    if (!from_major) std::reverse(p, p + l.s), std::reverse(q, q + l.s);
    return;
  }
  // A D-edge of a D-facet whose normals come from level 0's masks (facet_masks.h): from the
  // major's, else the minor's; the stencils then give its positions alone.
  auto from_base = [&](const HalfEdge& h) { return base->masks && base->masks->has(h.facet); };
  const bool major = base && l.s > 0 && from_base(d.major);
  const bool minor = base && l.s > 0 && !major && !d.minor.null() && from_base(d.minor);
  project_edge_nodes(sigma, e, src, position, normal, offset, !(major || minor));
  if (!major && !minor) return;
  const HalfEdge& h = major ? d.major : d.minor;
  V3* out = normal + l.edge_node(e, 0);
  base->masks->side_normals(h.facet, sigma, h.side, base->points, out);
  if (minor) std::reverse(out, out + l.s);
}

void MeshProcessor::project_edge_nodes(int sigma, int e, const V3* src, V3* position, V3* normal, const V3* offset,
                                       bool normals) const {
  const LevelLayout& l = lod_.layout(sigma);
  const int n = l.n;
  if (!fast_edge(e)) {
    load_strip(sigma, e, src);
    VertexDisk& disk = t_disk;
    for (int t = 1; t <= l.s; ++t) {
      strip_disk(sigma, e, t, disk);
      V3& p = position[l.edge_node(e, t - 1)];
      shader_.limit(disk, p, normal[l.edge_node(e, t - 1)]);
      if (offset) p = placed(p.x, p.y, p.z, offset);
    }
    return;
  }
  if (n < tile::kLongRow) {  // tag-free and short: the limit node by node
    load_strip(sigma, e, src);
    const Strip& s = t_strip;
    const V3 *A = s.a.data(), *B = s.b.data(), *C = s.c.data();
    for (int t = 1; t <= l.s; ++t) {
      V3 &p = position[l.edge_node(e, t - 1)], &q = normal[l.edge_node(e, t - 1)];
      if (s.quad_major) {  // counter-clockwise seen from the major D-facet, as strip_disk orders them
        const V3 ring[4] = {A[t + 1], B[t], A[t - 1], C[t]};
        const V3 diag[4] = {B[t + 1], B[t - 1], C[t - 1], C[t + 1]};
        if (normals) catmark_limit_regular(A[t], ring, diag, p, q);
        else p = catmark_limit_position(A[t], ring, diag);
      } else {
        const V3 ring[6] = {A[t + 1], B[t], B[t - 1], A[t - 1], C[t - 1], C[t]};
        loop_limit_regular(A[t], ring, p, q);
      }
      if (offset) p = placed(p.x, p.y, p.z, offset);
    }
    return;
  }
  // tag-free: the tile's limit stencils along row 1 (load_strip_rows)
  const bool quad = load_strip_rows(sigma, e, src);
  const tile::Tile& rows = t_strip_rows;
  tile::Planes& s = t_strip_planes;
  if (quad && !normals)  // the planes' normals then whatever the last strip left, overwritten by the caller
    tile::quad_limit_positions(rows.plane(0) + n, rows.plane(1) + n, rows.plane(2) + n, n, n, s.v[0][0].data(),
                               s.v[0][1].data(), s.v[0][2].data());
  else
    (quad ? tile::quad_limit_normals : tile::triangle_limit_normals)(
        rows.plane(0) + n, rows.plane(1) + n, rows.plane(2) + n, n, n, s.v[0][0].data(), s.v[0][1].data(),
        s.v[0][2].data(), s.normal[0].data(), s.normal[1].data(), s.normal[2].data());
  const float *px = s.v[0][0].data(), *py = s.v[0][1].data(), *pz = s.v[0][2].data();
  const float *nx = s.normal[0].data(), *ny = s.normal[1].data(), *nz = s.normal[2].data();
  V3 *p = position + l.edge_node(e, 0), *q = normal + l.edge_node(e, 0);
  for (int t = 1; t <= l.s; ++t) {
    p[t - 1] = placed(px[t], py[t], pz[t], offset);
    q[t - 1] = {nx[t], ny[t], nz[t]};
  }
}

void MeshProcessor::project(int sigma, const V3* src, V3* position, V3* normal, bool parallel, const V3* offset,
                            const BaseLevel* base) const {
  for_each(int(tiles_.size()), parallel, 32, [&](int i) {
    project_facets(sigma, tiles_[i], src, position, normal, offset, base);
    for (int32_t e : tile_edges_.of(i)) project_edge(sigma, e, src, position, normal, offset, base);
    for (int32_t v : tile_vertices_.of(i)) project_vertex(sigma, v, src, position, normal, offset, base);
  });
}

void MeshProcessor::project_vertex(int sigma, int v, const V3* src, V3* position, V3* normal, const V3* offset,
                                   const BaseLevel* base) const {
  if (atlas_.valence(v) == 0) {
    position[v] = src[v], normal[v] = {0, 0, 0};
  } else {
    VertexDisk& disk = t_disk;
    gather_vertex(sigma, v, src, disk);
    shader_.limit(disk, position[v], normal[v]);
    // The tangents from level 0 (vertex_tangents.h: float's rounding at this level's spacing).
    if (base && base->tangents.applies(v, sigma)) normal[v] = base->tangents.normal(v, base->points);
  }
  if (offset) position[v] = placed(position[v].x, position[v].y, position[v].z, offset);
}

void MeshProcessor::project(int sigma, const V3* src, V3* position, V3* normal, const Homes& homes,
                            bool parallel, const BaseLevel* base) const {
  const auto &f = homes.facets, &e = homes.edges, &v = homes.vertices;
  for_each(int(f.size()), parallel, 64, [&](int i) { project_facets(sigma, {f[i], -1}, src, position, normal, nullptr, base); });
  for_each(int(e.size()), parallel, 256, [&](int i) { project_edge(sigma, e[i], src, position, normal, nullptr, base); });
  for_each(int(v.size()), parallel, 512, [&](int i) { project_vertex(sigma, v[i], src, position, normal, nullptr, base); });
}

void MeshProcessor::vertex_shader_disk(int sigma, int v, const V3* src, bool limit, const DiskVisitor& visit) const {
  VertexDisk& disk = t_disk;
  if (atlas_.valence(v) == 0 || (!limit && atlas_.vertex_fans[v] > 1)) {  // as visit_vertex and project copy
    disk.resize(0, 0), disk.c = src[v];
  } else {
    gather_vertex(sigma, v, src, disk);
  }
  visit(uint32_t(v), &disk, nullptr);
}

void MeshProcessor::edge_shader_disks(int sigma, int e, const V3* src, bool limit, const DiskVisitor& visit) const {
  VertexDisk& disk = t_disk;
  EdgeDisk edge;
  const LevelLayout& target = lod_.layout(limit ? sigma : sigma + 1);
  const int n = lod_.layout(sigma).n;
  load_strip(sigma, e, src);
  for (int t = 0; !limit && t + 1 < n; ++t) {
    edge_disk(sigma, e, t, edge);
    visit(target.edge_node(e, 2 * t), nullptr, &edge);
  }
  for (int t = 1; t + 1 < n; ++t) {
    strip_disk(sigma, e, t, disk);
    visit(target.edge_node(e, limit ? t - 1 : 2 * t - 1), &disk, nullptr);
  }
}

void MeshProcessor::shader_disks(int sigma, const V3* src, bool limit, const DiskVisitor& visit) const {
  for (int v = 0; v < atlas_.num_vertices; ++v) vertex_shader_disk(sigma, v, src, limit, visit);
  for (int e = 0; e < atlas_.num_edges(); ++e)
    if (!fast_edge(e)) edge_shader_disks(sigma, e, src, limit, visit);
}

void MeshProcessor::adaptive_shader_disks(int sigma, const V3* src, bool limit, const Homes& homes,
                                          const DiskVisitor& visit, const Interpolation& interpolate) const {
  if (limit) {
    for (int v : homes.vertices) vertex_shader_disk(sigma, v, src, true, visit);
    for (int e : homes.edges)
      if (!fast_edge(e)) edge_shader_disks(sigma, e, src, true, visit);
    return;
  }
  for (int v = 0; v < atlas_.num_vertices; ++v) {
    if (vertex_readable(sigma, v)) vertex_shader_disk(sigma, v, src, false, visit);
    else interpolate(uint32_t(v), src[v], src[v]);
  }
  for (int e : lod_.edges_held(sigma + 1)) {
    if (!edge_readable(sigma, e))
      copied_edge_nodes(sigma, e, [&](uint32_t target, uint32_t i, uint32_t j) { interpolate(target, src[i], src[j]); });
    else if (!fast_edge(e))
      edge_shader_disks(sigma, e, src, false, visit);
  }
}

void MeshProcessor::adjust(int sigma, const V3* src, V3* dst, const Adjustment& shader) const {
  adjustment_disks(sigma, src, [&](uint32_t node, const VertexDisk& disk) {
    dst[node] = disk.edges == 0 ? disk.c : shader(disk);
  });
}

void MeshProcessor::adjustment_disks(int sigma, const V3* src, const AdjustmentVisitor& visit) const {
  const LevelLayout& l = lod_.layout(sigma);
  const int n = l.n;
  VertexDisk disk;
  for (int f = 0; f < atlas_.num_facets(); ++f) {
    const uint32_t* idx = lod_.facet(sigma, f);
    const int size = atlas_.facet_size[f];
    auto at = [&](int i, int j) { return src[idx[facet_offset(size, n, {i, j})]]; };
    for (int i = 1; i <= l.s; ++i)
      for (int j = 1; size == 4 ? j <= l.s : i + j <= l.s; ++j) {
        disk.c = at(i, j);
        if (size == 4) {
          disk.resize(4, 4);
          disk.e[0] = at(i, j + 1), disk.e[1] = at(i + 1, j), disk.e[2] = at(i, j - 1), disk.e[3] = at(i - 1, j);
          disk.d[0] = at(i + 1, j + 1), disk.d[1] = at(i + 1, j - 1), disk.d[2] = at(i - 1, j - 1), disk.d[3] = at(i - 1, j + 1);
        } else {
          disk.resize(6, 6);
          disk.e[0] = at(i, j + 1), disk.e[1] = at(i + 1, j), disk.e[2] = at(i + 1, j - 1);
          disk.e[3] = at(i, j - 1), disk.e[4] = at(i - 1, j), disk.e[5] = at(i - 1, j + 1);
          for (int k = 0; k < 6; ++k) disk.d[k] = disk.c;
        }
        for (int k = 0; k < disk.faces; ++k) disk.face_size[k] = uint8_t(size);
        visit(idx[facet_offset(size, n, {i, j})], disk);
      }
  }
  for (int e = 0; e < atlas_.num_edges(); ++e) {
    load_strip(sigma, e, src);
    for (int t = 1; t <= l.s; ++t) {
      strip_disk(sigma, e, t, disk);
      visit(l.edge_node(e, t - 1), disk);
    }
  }
  for (int v = 0; v < atlas_.num_vertices; ++v) {
    if (atlas_.valence(v) == 0) {
      disk.resize(0, 0), disk.c = src[v];
    } else {
      gather_vertex(sigma, v, src, disk);
    }
    visit(uint32_t(v), disk);
  }
}

}  // namespace sdb::mipgh
