#include "schemes/mipgh/processor.h"

#include <tbb/parallel_for.h>

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

// A D-facet's nodes of one level, gathered once through its index array (the work-group tile
// a GPU would stage in shared memory).
struct Tile {
  std::vector<V3> p;
  int n = 0;
  void load(const uint32_t* idx, int size, const V3* src) {
    n = size;
    p.resize(size_t(n) * n);
    for (int i = 0; i < n * n; ++i) p[i] = src[idx[i]];
  }
  const V3& at(int i, int j) const { return p[size_t(i) * n + j]; }
};

thread_local Tile t_tile;
thread_local VertexDisk t_disk;

}  // namespace

void MeshProcessor::visit_facet(int sigma, int f, const V3* src, V3* dst) const {
  const LevelLayout& to = lod_.layout(sigma + 1);
  Tile& t = t_tile;
  t.load(lod_.facet(sigma, f), lod_.layout(sigma).n, src);
  V3* out = dst + to.interior(f);
  const int m = to.n - 1;  // target rows and columns 1 .. m - 1 are inside the D-facet
  for (int r = 1; r < m; ++r) {
    const int a = r >> 1;
    if (r & 1) {  // between source rows a and a + 1: facet points and vertical edge points
      for (int c = 1; c < m; ++c) {
        const int b = c >> 1;
        *out++ = (c & 1) ? facet_vertex(t.at(a, b), t.at(a, b + 1), t.at(a + 1, b + 1), t.at(a + 1, b))
                         : edge_vertex(t.at(a, b), t.at(a + 1, b), t.at(a, b - 1), t.at(a + 1, b - 1),
                                       t.at(a, b + 1), t.at(a + 1, b + 1));
      }
    } else {  // on source row a: horizontal edge points and vertex points
      for (int c = 1; c < m; ++c) {
        const int b = c >> 1;
        *out++ = (c & 1) ? edge_vertex(t.at(a, b), t.at(a, b + 1), t.at(a - 1, b), t.at(a - 1, b + 1),
                                       t.at(a + 1, b), t.at(a + 1, b + 1))
                         : vertex_vertex4(t.at(a, b), t.at(a, b + 1), t.at(a + 1, b), t.at(a, b - 1), t.at(a - 1, b),
                                          t.at(a + 1, b + 1), t.at(a + 1, b - 1), t.at(a - 1, b - 1),
                                          t.at(a - 1, b + 1));
      }
    }
  }
}

void MeshProcessor::gather_edge_node(int sigma, int e, int along, const V3* src, VertexDisk& disk) const {
  const int n = lod_.layout(sigma).n;
  const DEdge& d = atlas_.edges[e];
  const uint32_t* f = lod_.facet(sigma, d.major.facet);
  auto A = [&](int t) { return src[f[side_offset(d.major.side, n, t, 0)]]; };
  auto B = [&](int t) { return src[f[side_offset(d.major.side, n, t, 1)]]; };
  const bool boundary = d.minor.null();
  disk.resize(boundary ? 3 : 4, boundary ? 2 : 4);
  // Counter-clockwise seen from the major D-facet: along +, into it, along -, into the minor one.
  disk.c = A(along);
  disk.e[0] = A(along + 1), disk.e[1] = B(along), disk.e[2] = A(along - 1);
  disk.d[0] = B(along + 1), disk.d[1] = B(along - 1);
  if (!boundary) {
    const uint32_t* g = lod_.facet(sigma, d.minor.facet);
    auto C = [&](int t) { return src[g[side_offset(d.minor.side, n, n - 1 - t, 1)]]; };
    disk.e[3] = C(along);
    disk.d[2] = C(along - 1), disk.d[3] = C(along + 1);
  }
  disk.sharpness = disk.child_sharpness = 0;
  for (int i = 0; i < disk.edges; ++i) disk.edge_sharpness[i] = disk.child_edge_sharpness[i] = 0;
  disk.edge_sharpness[0] = tags_.micro_edge(sigma, e, along);
  disk.edge_sharpness[2] = tags_.micro_edge(sigma, e, along - 1);
  if (sigma < lod_.depth()) {
    disk.child_edge_sharpness[0] = tags_.micro_edge(sigma + 1, e, 2 * along);
    disk.child_edge_sharpness[2] = tags_.micro_edge(sigma + 1, e, 2 * along - 1);
  }
}

void MeshProcessor::visit_edge(int sigma, int e, const V3* src, V3* dst) const {
  const LevelLayout& to = lod_.layout(sigma + 1);
  const int n = lod_.layout(sigma).n;
  const DEdge& d = atlas_.edges[e];
  const uint32_t* f = lod_.facet(sigma, d.major.facet);
  auto A = [&](int t) { return src[f[side_offset(d.major.side, n, t, 0)]]; };
  auto B = [&](int t) { return src[f[side_offset(d.major.side, n, t, 1)]]; };
  const uint32_t* g = d.minor.null() ? nullptr : lod_.facet(sigma, d.minor.facet);
  auto C = [&](int t) { return src[g[side_offset(d.minor.side, n, n - 1 - t, 1)]]; };
  const bool tagged = tags_.slot.size() && tags_.slot[e] >= 0;
  V3* out = dst + to.edge_node(e, 0);
  for (int k = 0; k < to.s; ++k) {
    const int tt = k + 1;  // position along the edge at sigma + 1
    if (tt & 1) {
      const int t = tt >> 1;
      if (!tagged) {
        out[k] = edge_vertex(A(t), A(t + 1), B(t), B(t + 1), C(t), C(t + 1));
        continue;
      }
      EdgeDisk disk;
      disk.faces = g ? 2 : 1;
      disk.v0 = A(t), disk.v1 = A(t + 1);
      disk.f[0][0] = B(t), disk.f[0][1] = B(t + 1);
      if (g) disk.f[1][0] = C(t), disk.f[1][1] = C(t + 1);
      disk.sharpness = tags_.micro_edge(sigma, e, t);
      disk.child_sharpness[0] = tags_.micro_edge(sigma + 1, e, 2 * t);
      disk.child_sharpness[1] = tags_.micro_edge(sigma + 1, e, 2 * t + 1);
      out[k] = shader_.edge_vertex(disk);
    } else {
      const int t = tt >> 1;
      if (!tagged) {
        out[k] = vertex_vertex4(A(t), A(t + 1), B(t), A(t - 1), C(t), B(t + 1), B(t - 1), C(t - 1), C(t + 1));
        continue;
      }
      VertexDisk& disk = t_disk;
      gather_edge_node(sigma, e, t, src, disk);
      out[k] = shader_.vertex_vertex(disk);
    }
  }
}

void MeshProcessor::gather_vertex(int sigma, int v, const V3* src, VertexDisk& disk) const {
  const int n = lod_.layout(sigma).n;
  const int begin = atlas_.ring_offsets[v], faces = atlas_.ring_offsets[v + 1] - begin;
  const bool boundary = atlas_.vertex_boundary[v];
  disk.resize(faces + boundary, faces);
  disk.c = src[v];
  const int last = (1 << sigma) - 1;
  const bool child = sigma < lod_.depth() && tags_.any;
  // The micro-edge of the side next to v: index 0 from the major halfedge's start.
  auto sharpness = [&](int level, int facet, int side, bool v_at_start) {
    const int e = atlas_.facet_edges[facet][side];
    const bool at_major_start = v_at_start != bool(atlas_.facet_side_minor[facet][side]);
    return tags_.micro_edge(level, e, at_major_start ? 0 : (level == sigma ? last : 2 * last + 1));
  };
  for (int i = 0; i < faces; ++i) {
    const HalfEdge& h = atlas_.ring[begin + i];
    const uint32_t* idx = lod_.facet(sigma, h.facet);
    disk.e[i] = src[idx[side_offset(h.side, n, 1, 0)]];
    disk.d[i] = src[idx[side_offset(h.side, n, 1, 1)]];
    disk.edge_sharpness[i] = tags_.any ? sharpness(sigma, h.facet, h.side, true) : 0.0f;
    disk.child_edge_sharpness[i] = child ? sharpness(sigma + 1, h.facet, h.side, true) : 0.0f;
  }
  if (boundary) {
    const HalfEdge& h = atlas_.ring[begin + faces - 1];
    const int side = (h.side + 3) & 3;
    disk.e[faces] = src[lod_.facet(sigma, h.facet)[side_offset(side, n, n - 2, 0)]];
    disk.edge_sharpness[faces] = tags_.any ? sharpness(sigma, h.facet, side, false) : 0.0f;
    disk.child_edge_sharpness[faces] = child ? sharpness(sigma + 1, h.facet, side, false) : 0.0f;
  }
  disk.sharpness = tags_.any ? tags_.vertex[sigma][v] : 0.0f;
  disk.child_sharpness = child ? tags_.vertex[sigma + 1][v] : 0.0f;
}

void MeshProcessor::visit_vertex(int sigma, int v, const V3* src, V3* dst) const {
  if (atlas_.valence(v) == 0) {  // in no face: carried along unchanged
    dst[v] = src[v];
    return;
  }
  VertexDisk& disk = t_disk;
  gather_vertex(sigma, v, src, disk);
  dst[v] = shader_.vertex_vertex(disk);
}

void MeshProcessor::step(int sigma, const V3* src, V3* dst, bool parallel) const {
  for_each(atlas_.num_facets(), parallel, 64, [&](int f) { visit_facet(sigma, f, src, dst); });
  for_each(atlas_.num_edges(), parallel, 256, [&](int e) { visit_edge(sigma, e, src, dst); });
  for_each(atlas_.num_vertices, parallel, 512, [&](int v) { visit_vertex(sigma, v, src, dst); });
}

void MeshProcessor::project_facet(int sigma, int f, const V3* src, V3* position, V3* normal) const {
  const LevelLayout& l = lod_.layout(sigma);
  Tile& t = t_tile;
  t.load(lod_.facet(sigma, f), l.n, src);
  const uint32_t first = l.interior(f);
  for (int i = 1; i <= l.s; ++i)
    for (int j = 1; j <= l.s; ++j) {
      const V3 e[4] = {t.at(i, j + 1), t.at(i + 1, j), t.at(i, j - 1), t.at(i - 1, j)};
      const V3 d[4] = {t.at(i + 1, j + 1), t.at(i + 1, j - 1), t.at(i - 1, j - 1), t.at(i - 1, j + 1)};
      const uint32_t node = first + uint32_t(i - 1) * l.s + (j - 1);
      CatmarkShader::limit_regular(t.at(i, j), e, d, position[node], normal[node]);
    }
}

void MeshProcessor::project_edge(int sigma, int e, const V3* src, V3* position, V3* normal) const {
  const LevelLayout& l = lod_.layout(sigma);
  const bool tagged = tags_.slot.size() && tags_.slot[e] >= 0;
  VertexDisk& disk = t_disk;
  for (int k = 0; k < l.s; ++k) {
    gather_edge_node(sigma, e, k + 1, src, disk);
    const uint32_t node = l.edge_node(e, k);
    if (tagged)
      shader_.limit(disk, position[node], normal[node]);
    else
      CatmarkShader::limit_regular(disk.c, disk.e.data(), disk.d.data(), position[node], normal[node]);
  }
}

void MeshProcessor::project(int sigma, const V3* src, V3* position, V3* normal, bool parallel) const {
  for_each(atlas_.num_facets(), parallel, 64, [&](int f) { project_facet(sigma, f, src, position, normal); });
  for_each(atlas_.num_edges(), parallel, 256, [&](int e) { project_edge(sigma, e, src, position, normal); });
  for_each(atlas_.num_vertices, parallel, 512, [&](int v) {
    if (atlas_.valence(v) == 0) {
      position[v] = src[v], normal[v] = {0, 0, 0};
      return;
    }
    VertexDisk& disk = t_disk;
    gather_vertex(sigma, v, src, disk);
    shader_.limit(disk, position[v], normal[v]);
  });
}

void compile_primitives(const DAtlas& atlas, const DLoD& lod, int depth, Tessellation& out) {
  const LevelLayout& l = lod.layout(depth);
  const int n = l.n;
  const float step = 1.0f / float(n - 1);
  out.coords.assign(l.num_nodes, SurfaceCoord{});
  auto own = [&](int f, int offset) {
    out.coords[lod.facet(depth, f)[offset]] = {uint32_t(f), float(offset % n) * step, float(offset / n) * step};
  };
  for (int f = 0; f < atlas.num_facets(); ++f)
    for (int i = 1; i <= l.s; ++i)
      for (int j = 1; j <= l.s; ++j) own(f, i * n + j);
  for (const DEdge& e : atlas.edges)
    for (int a = 1; a <= l.s; ++a) own(e.major.facet, side_offset(e.major.side, n, a, 0));
  for (int v = 0; v < atlas.num_vertices; ++v)
    if (atlas.valence(v) > 0) {
      const HalfEdge& h = atlas.ring[atlas.ring_offsets[v]];
      own(h.facet, side_offset(h.side, n, 0, 0));
    }
  out.triangles.clear();
  for (int f = 0; f < atlas.num_facets(); ++f) {
    if (atlas.facet_hole[f]) continue;
    const uint32_t* idx = lod.facet(depth, f);
    for (int i = 0; i + 1 < n; ++i)
      for (int j = 0; j + 1 < n; ++j) {
        const uint32_t a = idx[i * n + j], b = idx[i * n + j + 1], c = idx[(i + 1) * n + j + 1], d = idx[(i + 1) * n + j];
        out.triangles.insert(out.triangles.end(), {a, b, c, a, c, d});
      }
  }
}

std::vector<uint32_t> same_points_at(const DAtlas& atlas, const DLoD& lod, int sigma, int inner) {
  const int n = lod.layout(sigma).n, m = lod.layout(inner).n, shift = inner - sigma;
  std::vector<uint32_t> to(lod.layout(sigma).num_nodes);
  for (int v = 0; v < atlas.num_vertices; ++v) to[v] = v;  // D-vertices (bare ones included) keep their slot
  for (int f = 0; f < atlas.num_facets(); ++f) {
    const uint32_t *coarse = lod.facet(sigma, f), *fine = lod.facet(inner, f);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) to[coarse[i * n + j]] = fine[(i << shift) * m + (j << shift)];
  }
  return to;
}

}  // namespace sdb::mipgh
