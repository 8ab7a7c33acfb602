#include "schemes/geometry-image/masks.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sdb::gim {

namespace {

// Per-plane row pointers; `s` is the plane's side.
struct Rows3 {
  const float *up, *mid, *down;
};

inline Rows3 rows_at(const float* plane, int side, int row) {
  const float* mid = plane + static_cast<size_t>(row) * side;
  return {mid - side, mid, mid + side};
}

}  // namespace

std::vector<int> padding_gather_table(const CutSymmetry& sym) {
  const int side = sym.size() + 2;
  std::vector<int> table(static_cast<size_t>(side) * side);
  for (int row = 0; row < side; ++row)
    for (int col = 0; col < side; ++col) table[static_cast<size_t>(row) * side + col] = sym.vertex(col - 1, row - 1);
  return table;
}

void pad_pass(const std::vector<int>& gather, const Point3* control, PaddedImage& dst, RowRange rows) {
  const size_t side = static_cast<size_t>(dst.side);
  float* px = dst.plane(0);
  float* py = dst.plane(1);
  float* pz = dst.plane(2);
  for (size_t i = rows.begin * side; i < rows.end * side; ++i) {
    const Point3& p = control[gather[i]];
    px[i] = p[0], py[i] = p[1], pz[i] = p[2];
  }
}

void split_pass(const PaddedImage& src, PaddedImage& dst, RowRange rows) {
  const int s = src.side, d = dst.side;  // d = 2s - 1
  for (int c = 0; c < 3; ++c) {
    const float* in = src.plane(c);
    float* out = dst.plane(c);
    for (int j = rows.begin; j < rows.end; ++j) {
      const float* r0 = in + static_cast<size_t>(j >> 1) * s;
      float* o = out + static_cast<size_t>(j) * d;
      if ((j & 1) == 0) {
        for (int x = 0; x + 1 < s; ++x) {
          o[2 * x] = r0[x];
          o[2 * x + 1] = 0.5f * (r0[x] + r0[x + 1]);
        }
        o[d - 1] = r0[s - 1];
      } else {
        const float* r1 = r0 + s;
        for (int x = 0; x + 1 < s; ++x) {
          o[2 * x] = 0.5f * (r0[x] + r1[x]);
          // Diagonal pairs first: a half turn swaps r0[x] with r1[x+1] and r0[x+1] with r1[x].
          o[2 * x + 1] = 0.25f * ((r0[x] + r1[x + 1]) + (r0[x + 1] + r1[x]));
        }
        o[d - 1] = 0.5f * (r0[s - 1] + r1[s - 1]);
      }
    }
  }
}

void average_pass(const PaddedImage& src, PaddedImage& dst, RowRange rows) {
  const int s = src.side, d = dst.side;  // d = s - 2
  for (int c = 0; c < 3; ++c) {
    const float* in = src.plane(c);
    float* out = dst.plane(c);
    for (int j = rows.begin; j < rows.end; ++j) {
      const Rows3 r = rows_at(in, s, j + 1);
      float* o = out + static_cast<size_t>(j) * d;
      for (int i = 0; i < d; ++i) {
        const int x = i + 1;
        const float centre = r.mid[x];
        const float edges = (r.mid[x - 1] + r.mid[x + 1]) + (r.up[x] + r.down[x]);
        const float corners = (r.up[x - 1] + r.down[x + 1]) + (r.up[x + 1] + r.down[x - 1]);
        o[i] = ((4.0f * centre + 2.0f * edges) + corners) * 0.0625f;
      }
    }
  }
}

namespace {

// One destination row of the fused pass. `vertex_row`: the row lies on a source row (weights
// 1 6 1 across rows up/mid/down); otherwise it lies between source rows mid and down (1 1).
// Destination column i sits at L column i + 1: even i is an edge column between source columns
// i/2 and i/2 + 1, odd i the vertex column (i + 1)/2. Each iteration writes one of each, so the
// stores form pairs the compiler vectorises.
void split_average_row(const Rows3& r, bool vertex_row, int s, float* o) {
  if (vertex_row) {
    const float *up = r.up, *mid = r.mid, *down = r.down;
    auto edge = [&](int x) {  // 1/16 [1 6 1]^T [1 1]
      const float centre = mid[x] + mid[x + 1];
      const float corners = (up[x] + down[x + 1]) + (up[x + 1] + down[x]);
      return (6.0f * centre + corners) * 0.0625f;
    };
    for (int x = 0; x + 2 < s; ++x) {
      o[2 * x] = edge(x);
      const int v = x + 1;  // 1/64 [1 6 1]^T [1 6 1]
      const float edges = (mid[v - 1] + mid[v + 1]) + (up[v] + down[v]);
      const float corners = (up[v - 1] + down[v + 1]) + (up[v + 1] + down[v - 1]);
      o[2 * x + 1] = ((36.0f * mid[v] + 6.0f * edges) + corners) * 0.015625f;
    }
    o[2 * (s - 2)] = edge(s - 2);
  } else {
    const float* a = r.mid;   // source row above the new row
    const float* b = r.down;  // source row below it
    auto face = [&](int x) { return ((a[x] + b[x + 1]) + (a[x + 1] + b[x])) * 0.25f; };  // 1/4 [1 1]^T [1 1]
    for (int x = 0; x + 2 < s; ++x) {
      o[2 * x] = face(x);
      const int v = x + 1;  // 1/16 [1 1]^T [1 6 1]
      const float centre = a[v] + b[v];
      const float corners = (a[v - 1] + b[v + 1]) + (a[v + 1] + b[v - 1]);
      o[2 * x + 1] = (6.0f * centre + corners) * 0.0625f;
    }
    o[2 * (s - 2)] = face(s - 2);
  }
}

}  // namespace

void split_average_pass(const PaddedImage& src, PaddedImage& dst, RowRange rows) {
  const int s = src.side, d = dst.side;  // d = 2s - 3
  for (int c = 0; c < 3; ++c) {
    const float* in = src.plane(c);
    float* out = dst.plane(c);
    for (int j = rows.begin; j < rows.end; ++j) {
      // Destination row j is L row j + 1: even -> on source row (j + 1) / 2, odd -> between
      // source rows j / 2 and j / 2 + 1.
      const bool vertex_row = ((j + 1) & 1) == 0;
      const int mid = vertex_row ? (j + 1) / 2 : j / 2;
      const float* m = in + static_cast<size_t>(mid) * s;
      const Rows3 r = {vertex_row ? m - s : nullptr, m, m + s};
      split_average_row(r, vertex_row, s, out + static_cast<size_t>(j) * d);
    }
  }
}

// The E and T passes work through a row in chunks: each plane into a small SoA buffer (unit
// stride, vectorised), then interleaved into the Point3 output.
constexpr int kChunk = 256;

namespace {

// Rows y-1, y, y+1 of one plane around padded row y + 1, at the chunk's first sample.
inline Rows3 chunk_rows(const PaddedImage& src, int c, int y, int start) {
  const Rows3 r = rows_at(src.plane(c), src.side, y + 1);
  return {r.up + start + 1, r.mid + start + 1, r.down + start + 1};
}

// E of one plane along a chunk.
inline void limit_chunk(const Rows3& r, int count, float* dst) {
  const float *up = r.up, *mid = r.mid, *down = r.down;
  for (int i = 0; i < count; ++i) {
    const float edges = (mid[i - 1] + mid[i + 1]) + (up[i] + down[i]);
    const float corners = (up[i - 1] + down[i + 1]) + (up[i + 1] + down[i - 1]);
    dst[i] = ((16.0f * mid[i] + 4.0f * edges) + corners) * (1.0f / 36.0f);
  }
}

// 6 T_s and 6 T_t of one plane along a chunk. A half turn negates each difference and swaps the
// two outer ones, so the sum is negated exactly.
inline void tangent_chunk(const Rows3& r, int count, float* ts, float* tt) {
  const float *up = r.up, *mid = r.mid, *down = r.down;
  for (int i = 0; i < count; ++i) {
    ts[i] = 4.0f * (mid[i + 1] - mid[i - 1]) + ((up[i + 1] - up[i - 1]) + (down[i + 1] - down[i - 1]));
    tt[i] = 4.0f * (down[i] - up[i]) + ((down[i - 1] - up[i - 1]) + (down[i + 1] - up[i + 1]));
  }
}

// unit(T_s x T_t) along a chunk, planes in and out.
inline void normal_chunk(const float (*ts)[kChunk], const float (*tt)[kChunk], int count, float (*nn)[kChunk]) {
  constexpr float kTiny = std::numeric_limits<float>::min();
  for (int i = 0; i < count; ++i) {
    const float cx = ts[1][i] * tt[2][i] - ts[2][i] * tt[1][i];
    const float cy = ts[2][i] * tt[0][i] - ts[0][i] * tt[2][i];
    const float cz = ts[0][i] * tt[1][i] - ts[1][i] * tt[0][i];
    // + FLT_MIN keeps a zero cross product (only at the cut vertices, which
    // cut_vertex_normal_pass overwrites) finite and is below half an ulp of any length that is
    // not tiny; unlike a max() or a select it lets the loop vectorise.
    const float len2 = cx * cx + cy * cy + cz * cz + kTiny;
    const float inv = 1.0f / std::sqrt(len2);
    // + 0.0f turns -0 into +0: a zero tangent component is +0 on both sides of the cut (x - x is
    // +0), so a product with it can be -0 on one side and +0 on the other.
    nn[0][i] = cx * inv + 0.0f, nn[1][i] = cy * inv + 0.0f, nn[2][i] = cz * inv + 0.0f;
  }
}

inline void interleave(const float (*planes)[kChunk], int count, Point3* out) {
  for (int i = 0; i < count; ++i) out[i] = {planes[0][i], planes[1][i], planes[2][i]};
}

inline Point3 unit_cross(const float a[3], const float b[3]) {
  const float cx = a[1] * b[2] - a[2] * b[1];
  const float cy = a[2] * b[0] - a[0] * b[2];
  const float cz = a[0] * b[1] - a[1] * b[0];
  const float len2 = cx * cx + cy * cy + cz * cz;
  const float inv = len2 > 0.0f ? 1.0f / std::sqrt(len2) : 0.0f;
  return {cx * inv, cy * inv, cz * inv};
}

}  // namespace

// The E and T passes work through a row in chunks: each plane into a small SoA buffer (unit
// stride, vectorised), then interleaved into the Point3 output.
void limit_pass(const PaddedImage& src, Point3* positions, RowRange rows) {
  const int n = src.side - 2;
  float p[3][kChunk];
  for (int y = rows.begin; y < rows.end; ++y)
    for (int start = 0; start < n; start += kChunk) {
      const int count = std::min(kChunk, n - start);
      for (int c = 0; c < 3; ++c) limit_chunk(chunk_rows(src, c, y, start), count, p[c]);
      interleave(p, count, positions + static_cast<size_t>(y) * n + start);
    }
}

void normal_pass(const PaddedImage& src, Point3* normals, RowRange rows) {
  const int n = src.side - 2;
  float ts[3][kChunk], tt[3][kChunk], nn[3][kChunk];
  for (int y = rows.begin; y < rows.end; ++y)
    for (int start = 0; start < n; start += kChunk) {
      const int count = std::min(kChunk, n - start);
      for (int c = 0; c < 3; ++c) tangent_chunk(chunk_rows(src, c, y, start), count, ts[c], tt[c]);
      normal_chunk(ts, tt, count, nn);
      interleave(nn, count, normals + static_cast<size_t>(y) * n + start);
    }
}

void limit_normal_pass(const PaddedImage& src, Point3* positions, Point3* normals, RowRange rows) {
  const int n = src.side - 2;
  float p[3][kChunk], ts[3][kChunk], tt[3][kChunk], nn[3][kChunk];
  for (int y = rows.begin; y < rows.end; ++y)
    for (int start = 0; start < n; start += kChunk) {
      const int count = std::min(kChunk, n - start);
      for (int c = 0; c < 3; ++c) {
        const Rows3 r = chunk_rows(src, c, y, start);
        limit_chunk(r, count, p[c]);
        tangent_chunk(r, count, ts[c], tt[c]);
      }
      normal_chunk(ts, tt, count, nn);
      interleave(p, count, positions + static_cast<size_t>(y) * n + start);
      interleave(nn, count, normals + static_cast<size_t>(y) * n + start);
    }
}

std::array<CutVertexStencil, 4> cut_vertex_stencils(int n) {
  std::array<CutVertexStencil, 4> out{};
  if (n < 5) return out;
  const CutSymmetry sym(n);
  const int side = n + 2;
  for (int i = 0; i < 4; ++i) {
    const ImagePos c = sym.cut_vertices()[i], e = sym.inward(i), u = sym.along(i);
    auto padded = [&](int dx, int dy) { return (c.y + dy + 1) * side + (c.x + dx + 1); };
    out[i] = {c.y * n + c.x, padded(0, 0), padded(u.x, u.y), padded(e.x, e.y), padded(u.x + e.x, u.y + e.y),
              padded(e.x - u.x, e.y - u.y)};
  }
  return out;
}

void cut_vertex_normal_pass(const PaddedImage& src, const std::array<CutVertexStencil, 4>& stencils, Point3* normals) {
  if (src.side < 7) return;  // a 3 x 3 image (the octahedron) has no cut-vertex stencil
  for (const CutVertexStencil& st : stencils) {
    float t1[3], t2[3];
    for (int c = 0; c < 3; ++c) {
      const float* p = src.plane(c);
      t1[c] = p[st.u] - p[st.e];
      t2[c] = p[st.ue] - p[st.mu_e];
    }
    normals[st.output] = unit_cross(t2, t1);
  }
}

}  // namespace sdb::gim
