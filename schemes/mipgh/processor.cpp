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
// work-group tile a GPU would stage in shared memory): the stencils below then run along rows,
// one plane at a time, in SIMD lanes.
struct Tile {
  std::vector<float> plane[3];
  int n = 0;
  // A triangle's rows (n - i nodes each) go to the square's lower-left half.
  void load(const uint32_t* idx, int size, const V3* src, bool quad) {
    n = size;
    for (auto& p : plane) p.resize(size_t(n) * n);
    float *x = plane[0].data(), *y = plane[1].data(), *z = plane[2].data();
    if (quad) {
      for (int i = 0; i < n * n; ++i) {
        const V3 p = src[idx[i]];
        x[i] = p.x, y[i] = p.y, z[i] = p.z;
      }
      return;
    }
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        const V3 p = src[*idx++];
        x[i * n + j] = p.x, y[i * n + j] = p.y, z[i * n + j] = p.z;
      }
  }
};

struct RowScratch {
  std::vector<float> row[3], normal[3];
  void fit(size_t size) {
    for (int k = 0; k < 3; ++k) row[k].resize(size), normal[k].resize(size);
  }
};

// The nodes along a D-edge and the rows next to it in its two D-facets, read once per visit:
// a[t] on the edge, b[t] one in from the major side, c[t] one in from the minor side (t counted
// from the major halfedge's first corner).
struct Strip {
  std::vector<V3> a, b, c;
  bool quad_major = true, quad_minor = true;
};

thread_local Tile t_tile;
thread_local Strip t_strip;
thread_local RowScratch t_row;
thread_local VertexDisk t_disk;

// Target row r (1 <= r <= 2n - 3) of a D-facet's refined interior, one coordinate: out[c - 1] for
// columns c = 1 .. 2n - 3. Facet points and vertical edge points on odd rows, horizontal edge
// points and vertex points on even ones (Figure 20's stencils).
void refine_row(const float* p, int n, int r, float* out) {
  const int a = r >> 1;
  if (r & 1) {
    const float *top = p + size_t(a) * n, *bot = top + n;
    for (int b = 0; b + 1 < n; ++b)  // c = 2b + 1
      out[2 * b] = 0.25f * ((top[b] + bot[b + 1]) + (top[b + 1] + bot[b]));
    for (int b = 1; b + 1 < n; ++b)  // c = 2b
      out[2 * b - 1] = 0.375f * (top[b] + bot[b]) + 0.0625f * ((top[b - 1] + bot[b - 1]) + (top[b + 1] + bot[b + 1]));
    return;
  }
  const float *mid = p + size_t(a) * n, *up = mid - n, *dn = mid + n;
  for (int b = 0; b + 1 < n; ++b)
    out[2 * b] = 0.375f * (mid[b] + mid[b + 1]) + 0.0625f * ((up[b] + up[b + 1]) + (dn[b] + dn[b + 1]));
  for (int b = 1; b + 1 < n; ++b)
    out[2 * b - 1] = 0.5625f * mid[b] + 0.09375f * ((mid[b + 1] + mid[b - 1]) + (dn[b] + up[b])) +
                     0.015625f * ((dn[b + 1] + up[b - 1]) + (dn[b - 1] + up[b + 1]));
}

// Limit positions and normals of interior row i, Figure 21's stencils with T1 along the row and T2
// across it; all three planes at once (the cross product needs them), written through `s`.
void project_row(const Tile& t, int i, RowScratch& s) {
  const int n = t.n;
  float t1[3][64], t2[3][64];  // n <= 257 at depth 8: done in blocks of 64 columns
  for (int j0 = 1; j0 + 1 < n; j0 += 64) {
    const int count = std::min(64, n - 1 - j0);
    for (int k = 0; k < 3; ++k) {
      const float *mid = t.plane[k].data() + size_t(i) * n + j0, *up = mid - n, *dn = mid + n;
      float* o = s.row[k].data() + (j0 - 1);
      for (int j = 0; j < count; ++j) {
        const float e0 = mid[j + 1], e1 = dn[j], e2 = mid[j - 1], e3 = up[j];
        const float d0 = dn[j + 1], d1 = dn[j - 1], d2 = up[j - 1], d3 = up[j + 1];
        o[j] = (1.0f / 36) * (16.0f * mid[j] + 4.0f * ((e0 + e2) + (e1 + e3)) + ((d0 + d2) + (d1 + d3)));
        t1[k][j] = 4.0f * (e0 - e2) + ((d0 + d3) - (d1 + d2));
        t2[k][j] = 4.0f * (e1 - e3) + ((d0 + d1) - (d2 + d3));
      }
    }
    float *nx = s.normal[0].data() + (j0 - 1), *ny = s.normal[1].data() + (j0 - 1), *nz = s.normal[2].data() + (j0 - 1);
    for (int j = 0; j < count; ++j) {
      const float x = t1[1][j] * t2[2][j] - t1[2][j] * t2[1][j];
      const float y = t1[2][j] * t2[0][j] - t1[0][j] * t2[2][j];
      const float z = t1[0][j] * t2[1][j] - t1[1][j] * t2[0][j];
      const float l = std::sqrt(x * x + y * y + z * z);
      const float inv = l > 0 ? 1.0f / l : 1.0f;
      nx[j] = x * inv, ny[j] = y * inv, nz[j] = z * inv;
    }
  }
}

// Loop's refined interior of a triangular D-facet, target row r (1 <= r <= 2n - 4), one
// coordinate: out[c - 1] for columns c = 1 .. 2n - 3 - r. p holds the triangle's nodes in the
// square's lower-left half, (i, j) at p[i * n + j]. Even rows: horizontal edge points and vertex
// points; odd rows: diagonal and vertical edge points.
void refine_triangle_row(const float* p, int n, int r, float* out) {
  const int a = r >> 1, end = 2 * n - 3 - r;  // last column
  if (!(r & 1)) {
    const float *mid = p + size_t(a) * n, *up = mid + n, *dn = mid - n;  // rows a, a + 1, a - 1
    for (int b = 0; 2 * b + 1 <= end; ++b)  // c = 2b + 1: (a, b)-(a, b+1)
      out[2 * b] = 0.375f * (mid[b] + mid[b + 1]) + 0.125f * (up[b] + dn[b + 1]);
    for (int b = 1; 2 * b <= end; ++b)  // c = 2b: vertex (a, b)
      out[2 * b - 1] = 0.625f * mid[b] +
                       0.0625f * (((mid[b + 1] + mid[b - 1]) + (up[b] + dn[b])) + (up[b - 1] + dn[b + 1]));
    return;
  }
  const float *lo = p + size_t(a) * n, *hi = lo + n;  // rows a, a + 1
  for (int b = 0; 2 * b + 1 <= end; ++b)  // c = 2b + 1: (a, b+1)-(a+1, b)
    out[2 * b] = 0.375f * (lo[b + 1] + hi[b]) + 0.125f * (lo[b] + hi[b + 1]);
  for (int b = 1; 2 * b <= end; ++b)  // c = 2b: (a, b)-(a+1, b)
    out[2 * b - 1] = 0.375f * (lo[b] + hi[b]) + 0.125f * (lo[b + 1] + hi[b - 1]);
}

// Loop's regular limit along interior row i of a triangle (columns 1 .. n - 2 - i), as
// loop_limit_regular: ring (i, j+1), (i+1, j), (i+1, j-1), (i, j-1), (i-1, j), (i-1, j+1).
void project_triangle_row(const Tile& t, int i, RowScratch& s) {
  const int n = t.n, count = n - 2 - i;
  float t1[3][64], t2[3][64];
  for (int j0 = 1; j0 <= count; j0 += 64) {
    const int c = std::min(64, count - j0 + 1);
    for (int k = 0; k < 3; ++k) {
      const float *mid = t.plane[k].data() + size_t(i) * n + j0, *up = mid + n, *dn = mid - n;
      float* o = s.row[k].data() + (j0 - 1);
      for (int j = 0; j < c; ++j) {
        const float e0 = mid[j + 1], e1 = up[j], e2 = up[j - 1], e3 = mid[j - 1], e4 = dn[j], e5 = dn[j + 1];
        o[j] = 0.5f * mid[j] + (1.0f / 12) * (((e0 + e3) + (e1 + e4)) + (e2 + e5));
        t1[k][j] = (e0 - e3) + 0.5f * ((e1 - e2) - (e4 - e5));
        t2[k][j] = (e1 + e2) - (e4 + e5);
      }
    }
    float *nx = s.normal[0].data() + (j0 - 1), *ny = s.normal[1].data() + (j0 - 1), *nz = s.normal[2].data() + (j0 - 1);
    for (int j = 0; j < c; ++j) {
      const float x = t1[1][j] * t2[2][j] - t1[2][j] * t2[1][j];
      const float y = t1[2][j] * t2[0][j] - t1[0][j] * t2[2][j];
      const float z = t1[0][j] * t2[1][j] - t1[1][j] * t2[0][j];
      const float l = std::sqrt(x * x + y * y + z * z);
      const float inv = l > 0 ? 1.0f / l : 1.0f;
      nx[j] = x * inv, ny[j] = y * inv, nz[j] = z * inv;
    }
  }
}

}  // namespace

void MeshProcessor::visit_facet(int sigma, int f, const V3* src, V3* dst) const {
  const LevelLayout& to = lod_.layout(sigma + 1);
  const int n = lod_.layout(sigma).n, width = to.s;  // target rows and columns 1 .. width
  Tile& t = t_tile;
  const bool quad = atlas_.facet_size[f] == 4;
  t.load(lod_.facet(sigma, f), n, src, quad);
  V3* out = dst + to.interior(f);
  RowScratch& s = t_row;
  s.fit(width);
  for (int r = 1; r <= width; ++r) {
    const int count = quad ? width : width - r;  // a triangle's row r holds 2n - 3 - r interior nodes
    for (int k = 0; k < 3; ++k)
      quad ? refine_row(t.plane[k].data(), n, r, s.row[k].data())
           : refine_triangle_row(t.plane[k].data(), n, r, s.row[k].data());
    const float *x = s.row[0].data(), *y = s.row[1].data(), *z = s.row[2].data();
    for (int c = 0; c < count; ++c) out[c] = {x[c], y[c], z[c]};
    out += count;
  }
}

MeshProcessor::MeshProcessor(const DAtlas& atlas, const DLoD& lod, const EdgeTags& tags, const MeshShader& shader)
    : atlas_(atlas), lod_(lod), tags_(tags), shader_(shader), vertex_order_(atlas.num_vertices) {
  // A D-vertex's ring lies in the D-facets around it, far apart in memory at fine levels: visited
  // in the order of their first D-facet they follow the facets' storage instead of jumping.
  auto first = [&](int v) { return atlas.valence(v) ? atlas.ring[atlas.ring_offsets[v]].facet : -1; };
  for (int v = 0; v < atlas.num_vertices; ++v) vertex_order_[v] = v;
  std::stable_sort(vertex_order_.begin(), vertex_order_.end(), [&](int a, int b) { return first(a) < first(b); });
}

void MeshProcessor::load_strip(int sigma, int e, const V3* src) const {
  const int n = lod_.layout(sigma).n;
  const DEdge& d = atlas_.edges[e];
  Strip& s = t_strip;
  s.a.resize(n), s.b.resize(n), s.c.resize(n);
  const int fs = atlas_.facet_size[d.major.facet];
  const uint32_t* f = lod_.facet(sigma, d.major.facet);
  for (int t = 0; t < n; ++t) s.a[t] = src[f[facet_side_offset(fs, d.major.side, n, t, 0)]];
  // the row one in: n nodes in a quad, n - 1 in a triangle (node t next to a[t] and a[t + 1])
  for (int t = 0; t < n - (fs == 3); ++t) s.b[t] = src[f[facet_side_offset(fs, d.major.side, n, t, 1)]];
  s.quad_major = fs == 4;
  if (d.minor.null()) return;
  const int gs = atlas_.facet_size[d.minor.facet];
  const uint32_t* g = lod_.facet(sigma, d.minor.facet);
  s.quad_minor = gs == 4;
  // c[t] runs the major's way: a quad's node across from a[t]; a triangle's between a[t], a[t + 1]
  const int last = gs == 4 ? n - 1 : n - 2;
  for (int t = 0; t <= last; ++t) s.c[t] = src[g[facet_side_offset(gs, d.minor.side, n, last - t, 1)]];
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
  for_each(atlas_.num_vertices, parallel, 512, [&](int i) { visit_vertex(sigma, vertex_order_[i], src, dst); });
}

void MeshProcessor::project_facet(int sigma, int f, const V3* src, V3* position, V3* normal) const {
  const LevelLayout& l = lod_.layout(sigma);
  Tile& t = t_tile;
  const bool quad = atlas_.facet_size[f] == 4;
  t.load(lod_.facet(sigma, f), l.n, src, quad);
  const uint32_t first = l.interior(f);
  if (!quad) {  // Loop's regular limit at every interior node, row-major
    RowScratch& s = t_row;
    s.fit(l.s);
    V3 *p = position + first, *q = normal + first;
    for (int i = 1; i + 2 < l.n; ++i) {
      project_triangle_row(t, i, s);
      const int count = l.n - 2 - i;
      for (int j = 0; j < count; ++j) {
        p[j] = {s.row[0][j], s.row[1][j], s.row[2][j]};
        q[j] = {s.normal[0][j], s.normal[1][j], s.normal[2][j]};
      }
      p += count, q += count;
    }
    return;
  }
  RowScratch& s = t_row;
  s.fit(l.s);
  for (int i = 1; i <= l.s; ++i) {
    project_row(t, i, s);
    V3 *p = position + first + size_t(i - 1) * l.s, *q = normal + first + size_t(i - 1) * l.s;
    for (int j = 0; j < l.s; ++j) {
      p[j] = {s.row[0][j], s.row[1][j], s.row[2][j]};
      q[j] = {s.normal[0][j], s.normal[1][j], s.normal[2][j]};
    }
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
