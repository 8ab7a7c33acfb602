#include "schemes/mipgh/processor.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

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

// A D-facet's nodes of one level, gathered once through its index array into three planes (the
// work-group tile a GPU would stage in shared memory). A plane is the n x n square, a triangle in
// its lower-left half (row i holds n - i nodes), with n + 1 floats of padding on either side: the
// stencils then run over the whole square as one long SIMD loop with fixed neighbour offsets
// (+-1 along a row, +-n across), and the values at squares no target uses are dropped.
struct Tile {
  std::vector<float> storage[3];
  int n = 0;
  float* plane(int k) { return storage[k].data() + n + 1; }
  const float* plane(int k) const { return storage[k].data() + n + 1; }
  void load(const uint32_t* idx, int size, const V3* src, bool quad) {
    if (n != size)
      for (auto& s : storage) s.assign(size_t(size) * size + 2 * (size + 1), 0.0f);
    n = size;
    float *x = plane(0), *y = plane(1), *z = plane(2);
    // float by float: a V3 copied whole goes through the stack (store forwarding on every node)
    const float* base = &src[0].x;
    if (quad) {
      for (int i = 0; i < n * n; ++i) {
        const float* p = base + size_t(idx[i]) * 3;
        x[i] = p[0], y[i] = p[1], z[i] = p[2];
      }
      return;
    }
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        const float* p = base + size_t(*idx++) * 3;
        x[i * n + j] = p[0], y[i * n + j] = p[1], z[i * n + j] = p[2];
      }
  }
};

// The stencils' results over a tile's square: four classes of target per source square L = (a, b)
// (the target at (2a + r, 2b + c) for class 2r + c), or the limit position and two tangents.
struct Planes {
  std::vector<float> v[4][3], normal[3];
  size_t size = 0;
  void fit(size_t wanted) {
    if (wanted == size) return;
    size = wanted;
    for (auto& c : v)
      for (auto& p : c) p.resize(size);
    for (auto& p : normal) p.resize(size);
  }
};

// The nodes along a D-edge and the rows next to it in its two D-facets, read once per visit:
// a[t] on the edge, b[t] one in from the major side, c[t] one in from the minor side (t counted
// from the major halfedge's first corner).
struct Strip {
  std::vector<V3> a, b, c;
  bool quad_major = true, quad_minor = true;
};

// The tile's loops in AVX2 lanes where the CPU has them, SSE2 otherwise (as the fragments' kernel).
#define SDB_TILE_CLONES __attribute__((target_clones("avx2", "default")))

thread_local Tile t_tile;
thread_local Strip t_strip;
thread_local Planes t_planes;
thread_local VertexDisk t_disk;

// Figure 20's stencils at every square of one coordinate's plane: vertex points (class 0),
// horizontal edge points (1), vertical ones (2), facet points (3).
SDB_TILE_CLONES void quad_classes(const float* __restrict P, int n, float* __restrict vv, float* __restrict eh,
                  float* __restrict ev, float* __restrict fv) {
  for (int L = 0; L < n * n; ++L) {
    vv[L] = 0.5625f * P[L] + 0.09375f * ((P[L + 1] + P[L - 1]) + (P[L + n] + P[L - n])) +
            0.015625f * ((P[L + n + 1] + P[L - n - 1]) + (P[L + n - 1] + P[L - n + 1]));
    eh[L] = 0.375f * (P[L] + P[L + 1]) + 0.0625f * ((P[L - n] + P[L - n + 1]) + (P[L + n] + P[L + n + 1]));
    ev[L] = 0.375f * (P[L] + P[L + n]) + 0.0625f * ((P[L - 1] + P[L + n - 1]) + (P[L + 1] + P[L + n + 1]));
    fv[L] = 0.25f * ((P[L] + P[L + n + 1]) + (P[L + 1] + P[L + n]));
  }
}

// Loop's, in a triangle's square: vertex points (class 0), edge points of (a, b)-(a, b+1) (1),
// (a, b)-(a+1, b) (2) and the diagonal (a, b+1)-(a+1, b) (3).
SDB_TILE_CLONES void triangle_classes(const float* __restrict P, int n, float* __restrict vv, float* __restrict eh,
                      float* __restrict ev, float* __restrict ed) {
  for (int L = 0; L < n * n; ++L) {
    vv[L] = 0.625f * P[L] + 0.0625f * (((P[L + 1] + P[L - 1]) + (P[L + n] + P[L - n])) + (P[L + n - 1] + P[L - n + 1]));
    eh[L] = 0.375f * (P[L] + P[L + 1]) + 0.125f * (P[L + n] + P[L - n + 1]);
    ev[L] = 0.375f * (P[L] + P[L + n]) + 0.125f * (P[L + 1] + P[L + n - 1]);
    ed[L] = 0.375f * (P[L + 1] + P[L + n]) + 0.125f * (P[L] + P[L + n + 1]);
  }
}

// The limit position (class 0) and the two tangents (1, 2) at every square: Catmull-Clark's
// (16, 4, 1)/36 and Figure 21's stencils (T1 along a row, T2 across), or Loop's 1/2, 1/12 and its
// regular tangents, as catmark_limit_regular and loop_limit_regular compute them.
SDB_TILE_CLONES void quad_limit(const float* __restrict P, int n, float* __restrict pos, float* __restrict t1, float* __restrict t2) {
  for (int L = 0; L < n * n; ++L) {
    const float e0 = P[L + 1], e1 = P[L + n], e2 = P[L - 1], e3 = P[L - n];
    const float d0 = P[L + n + 1], d1 = P[L + n - 1], d2 = P[L - n - 1], d3 = P[L - n + 1];
    pos[L] = (1.0f / 36) * (16.0f * P[L] + 4.0f * ((e0 + e2) + (e1 + e3)) + ((d0 + d2) + (d1 + d3)));
    t1[L] = 4.0f * (e0 - e2) + ((d0 + d3) - (d1 + d2));
    t2[L] = 4.0f * (e1 - e3) + ((d0 + d1) - (d2 + d3));
  }
}
SDB_TILE_CLONES void triangle_limit(const float* __restrict P, int n, float* __restrict pos, float* __restrict t1,
                    float* __restrict t2) {
  for (int L = 0; L < n * n; ++L) {
    const float e0 = P[L + 1], e1 = P[L + n], e2 = P[L + n - 1], e3 = P[L - 1], e4 = P[L - n], e5 = P[L - n + 1];
    pos[L] = 0.5f * P[L] + (1.0f / 12) * (((e0 + e3) + (e1 + e4)) + (e2 + e5));
    t1[L] = (e0 - e3) + 0.5f * ((e1 - e2) - (e4 - e5));
    t2[L] = (e1 + e2) - (e4 + e5);
  }
}

// Unit T1 x T2 at every square.
SDB_TILE_CLONES void unit_normals(const float* __restrict ax, const float* __restrict ay, const float* __restrict az,
                                  const float* __restrict bx, const float* __restrict by, const float* __restrict bz,
                                  float* __restrict nx, float* __restrict ny, float* __restrict nz, int count) {
  for (int L = 0; L < count; ++L) {
    const float x = ay[L] * bz[L] - az[L] * by[L], y = az[L] * bx[L] - ax[L] * bz[L], z = ax[L] * by[L] - ay[L] * bx[L];
    const float l2 = x * x + y * y + z * z;
    const float inv = 1.0f / std::sqrt(l2 + 1e-37f);  // a zero normal stays zero; no branch, so SIMD lanes
    nx[L] = x * inv, ny[L] = y * inv, nz[L] = z * inv;
  }
}

}  // namespace

void MeshProcessor::visit_facet(int sigma, int f, const V3* src, V3* dst) const {
  const int n = lod_.layout(sigma).n, width = lod_.layout(sigma + 1).s;  // target rows, columns 1 .. width
  const bool quad = atlas_.facet_size[f] == 4;
  Tile& t = t_tile;
  Planes& s = t_planes;
  t.load(lod_.facet(sigma, f), n, src, quad);
  s.fit(size_t(n) * n);
  for (int k = 0; k < 3; ++k)
    (quad ? quad_classes : triangle_classes)(t.plane(k), n, s.v[0][k].data(), s.v[1][k].data(), s.v[2][k].data(),
                                             s.v[3][k].data());
  V3* out = dst + lod_.layout(sigma + 1).interior(f);
  for (int r = 1; r <= width; ++r) {
    // columns alternate between two classes: odd columns from `a`, even ones from `b`
    const int row = (r >> 1) * n, odd = (r & 1) << 1, end = quad ? width : width - r;
    const float *ax = s.v[odd | 1][0].data() + row, *ay = s.v[odd | 1][1].data() + row, *az = s.v[odd | 1][2].data() + row;
    const float *bx = s.v[odd][0].data() + row, *by = s.v[odd][1].data() + row, *bz = s.v[odd][2].data() + row;
    for (int c = 1; c <= end; ++c) {
      const int L = c >> 1;
      *out++ = (c & 1) ? V3{ax[L], ay[L], az[L]} : V3{bx[L], by[L], bz[L]};
    }
  }
}

MeshProcessor::MeshProcessor(const DAtlas& atlas, const DLoD& lod, const EdgeTags& tags, const MeshShader& shader)
    : atlas_(atlas), lod_(lod), tags_(tags), shader_(shader), vertex_order_(atlas.num_vertices) {
  // A D-vertex's ring lies in the D-facets around it, far apart in memory at fine levels: visited
  // in the order of their first D-facet they follow the facets' storage instead of jumping.
  auto first = [&](int v) { return atlas.valence(v) ? atlas.ring[atlas.ring_offsets[v]].facet : -1; };
  for (int v = 0; v < atlas.num_vertices; ++v) vertex_order_[v] = v;
  std::stable_sort(vertex_order_.begin(), vertex_order_.end(), [&](int a, int b) { return first(a) < first(b); });
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

void MeshProcessor::load_strip(int sigma, int e, const V3* src) const {
  const int n = lod_.layout(sigma).n;
  const DEdge& d = atlas_.edges[e];
  Strip& s = t_strip;
  s.a.resize(n), s.b.resize(n), s.c.resize(n);
  const int fs = atlas_.facet_size[d.major.facet];
  const uint32_t* f = lod_.facet(sigma, d.major.facet);
  const int32_t* on = side_rows(sigma, fs, d.major.side, 0);
  const int32_t* in = side_rows(sigma, fs, d.major.side, 1);
  for (int t = 0; t < n; ++t) s.a[t] = src[f[on[t]]];
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
  const int back = k;
  disk.e[k++] = s.a[t - 1];
  if (!boundary) {
    if (s.quad_minor) {
      disk.d[q++] = s.c[t - 1], disk.e[k++] = s.c[t], disk.d[q++] = s.c[t + 1];
    } else {
      disk.d[q++] = s.a[t], disk.e[k++] = s.c[t - 1], disk.d[q++] = s.a[t], disk.e[k++] = s.c[t], disk.d[q++] = s.a[t];
    }
  }
  disk.sharpness = disk.child_sharpness = 0;
  for (int i = 0; i < disk.edges; ++i) disk.edge_sharpness[i] = disk.child_edge_sharpness[i] = 0;
  disk.edge_sharpness[0] = tags_.micro_edge(sigma, e, t);
  disk.edge_sharpness[back] = tags_.micro_edge(sigma, e, t - 1);
  if (sigma < lod_.depth()) {
    disk.child_edge_sharpness[0] = tags_.micro_edge(sigma + 1, e, 2 * t);
    disk.child_edge_sharpness[back] = tags_.micro_edge(sigma + 1, e, 2 * t - 1);
  }
}

void MeshProcessor::visit_edge(int sigma, int e, const V3* src, V3* dst) const {
  const DEdge& d = atlas_.edges[e];
  load_strip(sigma, e, src);
  const Strip& s = t_strip;
  const V3 *A = s.a.data(), *B = s.b.data(), *C = s.c.data();
  const int n = lod_.layout(sigma).n;
  V3* out = dst + lod_.layout(sigma + 1).edge_node(e, 0);
  const bool boundary = d.minor.null();
  if (tags_.slot[e] < 0 && !boundary && s.quad_major == s.quad_minor) {  // tag-free: the fast paths
    if (s.quad_major) {  // Figure 20
      for (int t = 0; t + 1 < n; ++t) out[2 * t] = edge_vertex(A[t], A[t + 1], B[t], B[t + 1], C[t], C[t + 1]);
      for (int t = 1; t + 1 < n; ++t)
        out[2 * t - 1] = vertex_vertex4(A[t], A[t + 1], B[t], A[t - 1], C[t], B[t + 1], B[t - 1], C[t - 1], C[t + 1]);
    } else {  // Loop
      for (int t = 0; t + 1 < n; ++t) out[2 * t] = loop_edge_vertex(A[t], A[t + 1], B[t], C[t]);
      for (int t = 1; t + 1 < n; ++t)
        out[2 * t - 1] = loop_vertex6(A[t], A[t + 1], B[t], B[t - 1], A[t - 1], C[t - 1], C[t]);
    }
    return;
  }
  for (int t = 0; t + 1 < n; ++t) {
    EdgeDisk disk;
    disk.faces = boundary ? 1 : 2;
    disk.v0 = A[t], disk.v1 = A[t + 1];
    disk.f[0][0] = B[t], disk.f[0][1] = s.quad_major ? B[t + 1] : B[t];
    if (!boundary) disk.f[1][0] = C[t], disk.f[1][1] = s.quad_minor ? C[t + 1] : C[t];
    disk.sharpness = tags_.micro_edge(sigma, e, t);
    disk.child_sharpness[0] = tags_.micro_edge(sigma + 1, e, 2 * t);
    disk.child_sharpness[1] = tags_.micro_edge(sigma + 1, e, 2 * t + 1);
    out[2 * t] = shader_.edge_vertex(disk);
  }
  VertexDisk& disk = t_disk;
  for (int t = 1; t + 1 < n; ++t) {
    strip_disk(sigma, e, t, disk);
    out[2 * t - 1] = shader_.vertex_vertex(disk);
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
    const int size = atlas_.facet_size[h.facet];
    disk.e[i] = src[idx[facet_side_offset(size, h.side, n, 1, 0)]];
    // a quad's corner across from v (a triangle has none: Loop's masks weigh no faces)
    disk.d[i] = size == 4 ? src[idx[side_offset(h.side, n, 1, 1)]] : disk.c;
    disk.edge_sharpness[i] = tags_.any ? sharpness(sigma, h.facet, h.side, true) : 0.0f;
    disk.child_edge_sharpness[i] = child ? sharpness(sigma + 1, h.facet, h.side, true) : 0.0f;
  }
  if (boundary) {
    const HalfEdge& h = atlas_.ring[begin + faces - 1];
    const int size = atlas_.facet_size[h.facet], side = atlas_.prev(h.facet, h.side);
    disk.e[faces] = src[lod_.facet(sigma, h.facet)[facet_side_offset(size, side, n, n - 2, 0)]];
    disk.edge_sharpness[faces] = tags_.any ? sharpness(sigma, h.facet, side, false) : 0.0f;
    disk.child_edge_sharpness[faces] = child ? sharpness(sigma + 1, h.facet, side, false) : 0.0f;
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

void MeshProcessor::step(int sigma, const V3* src, V3* dst, bool parallel) const {
  for_each(atlas_.num_facets(), parallel, 64, [&](int f) { visit_facet(sigma, f, src, dst); });
  for_each(atlas_.num_edges(), parallel, 256, [&](int e) { visit_edge(sigma, e, src, dst); });
  for_each(atlas_.num_vertices, parallel, 512, [&](int i) { visit_vertex(sigma, vertex_order_[i], src, dst); });
}

void MeshProcessor::project_facet(int sigma, int f, const V3* src, V3* position, V3* normal) const {
  const LevelLayout& l = lod_.layout(sigma);
  const int n = l.n;
  const bool quad = atlas_.facet_size[f] == 4;
  Tile& t = t_tile;
  Planes& s = t_planes;
  t.load(lod_.facet(sigma, f), n, src, quad);
  s.fit(size_t(n) * n);
  for (int k = 0; k < 3; ++k)
    (quad ? quad_limit : triangle_limit)(t.plane(k), n, s.v[0][k].data(), s.v[1][k].data(), s.v[2][k].data());
  unit_normals(s.v[1][0].data(), s.v[1][1].data(), s.v[1][2].data(), s.v[2][0].data(), s.v[2][1].data(),
               s.v[2][2].data(), s.normal[0].data(), s.normal[1].data(), s.normal[2].data(), n * n);
  const uint32_t first = l.interior(f);
  V3 *p = position + first, *q = normal + first;
  const float *px = s.v[0][0].data(), *py = s.v[0][1].data(), *pz = s.v[0][2].data();
  const float *nx = s.normal[0].data(), *ny = s.normal[1].data(), *nz = s.normal[2].data();
  for (int i = 1; i <= l.s; ++i)
    for (int j = 1; quad ? j <= l.s : i + j <= l.s; ++j, ++p, ++q) {
      const int L = i * n + j;
      *p = {px[L], py[L], pz[L]};
      *q = {nx[L], ny[L], nz[L]};
    }
}

void MeshProcessor::project_edge(int sigma, int e, const V3* src, V3* position, V3* normal) const {
  const LevelLayout& l = lod_.layout(sigma);
  const DEdge& d = atlas_.edges[e];
  load_strip(sigma, e, src);
  const Strip& s = t_strip;
  if (tags_.slot[e] >= 0 || d.minor.null() || s.quad_major != s.quad_minor) {
    VertexDisk& disk = t_disk;
    for (int t = 1; t <= l.s; ++t) {
      strip_disk(sigma, e, t, disk);
      shader_.limit(disk, position[l.edge_node(e, t - 1)], normal[l.edge_node(e, t - 1)]);
    }
    return;
  }
  const V3 *A = s.a.data(), *B = s.b.data(), *C = s.c.data();
  for (int t = 1; t <= l.s; ++t) {
    V3 &p = position[l.edge_node(e, t - 1)], &q = normal[l.edge_node(e, t - 1)];
    if (s.quad_major) {  // counter-clockwise seen from the major D-facet, as strip_disk orders them
      const V3 ring[4] = {A[t + 1], B[t], A[t - 1], C[t]};
      const V3 diag[4] = {B[t + 1], B[t - 1], C[t - 1], C[t + 1]};
      catmark_limit_regular(A[t], ring, diag, p, q);
    } else {
      const V3 ring[6] = {A[t + 1], B[t], B[t - 1], A[t - 1], C[t - 1], C[t]};
      loop_limit_regular(A[t], ring, p, q);
    }
  }
}

void MeshProcessor::project(int sigma, const V3* src, V3* position, V3* normal, bool parallel) const {
  for_each(atlas_.num_facets(), parallel, 64, [&](int f) { project_facet(sigma, f, src, position, normal); });
  for_each(atlas_.num_edges(), parallel, 256, [&](int e) { project_edge(sigma, e, src, position, normal); });
  for_each(atlas_.num_vertices, parallel, 512, [&](int i) {
    const int v = vertex_order_[i];
    if (atlas_.valence(v) == 0) {
      position[v] = src[v], normal[v] = {0, 0, 0};
      return;
    }
    VertexDisk& disk = t_disk;
    gather_vertex(sigma, v, src, disk);
    shader_.limit(disk, position[v], normal[v]);
  });
}

void MeshProcessor::adjust(int sigma, const V3* src, V3* dst, const Adjustment& shader) const {
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
        dst[idx[facet_offset(size, n, {i, j})]] = shader(disk);
      }
  }
  for (int e = 0; e < atlas_.num_edges(); ++e) {
    load_strip(sigma, e, src);
    for (int t = 1; t <= l.s; ++t) {
      strip_disk(sigma, e, t, disk);
      dst[l.edge_node(e, t - 1)] = shader(disk);
    }
  }
  for (int v = 0; v < atlas_.num_vertices; ++v) {
    if (atlas_.valence(v) == 0) {
      dst[v] = src[v];
      continue;
    }
    gather_vertex(sigma, v, src, disk);
    dst[v] = shader(disk);
  }
}

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
