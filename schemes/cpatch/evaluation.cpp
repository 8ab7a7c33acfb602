#include "schemes/cpatch/evaluation.h"

#include <algorithm>
#include <limits>

#include "schemes/cpatch/bernstein.h"
#include "schemes/cpatch/conversion.h"
#include "schemes/cpatch/patch_control.h"

namespace sdb::cpatch {
namespace {

// Unit normals du x dv into the scratch's u arrays, in place. A degenerate tangent frame (only
// from degenerate control meshes) gets (0, 0, 1) so that every normal stays unit length. Written
// without branches (the division is unconditional) so that the loop vectorises.
void normals_in_place(PatchScratch& s, int count) {
  float* __restrict ux = s.ux;
  float* __restrict uy = s.uy;
  float* __restrict uz = s.uz;
  const float* __restrict vx = s.vx;
  const float* __restrict vy = s.vy;
  const float* __restrict vz = s.vz;
#pragma omp simd
  for (int k = 0; k < count; ++k) {
    const float nx = uy[k] * vz[k] - uz[k] * vy[k];
    const float ny = uz[k] * vx[k] - ux[k] * vz[k];
    const float nz = ux[k] * vy[k] - uy[k] * vx[k];
    const float len2 = nx * nx + ny * ny + nz * nz;
    // + FLT_MIN keeps the division finite without a branch; it changes no normal length in range.
    const float inv = 1.0f / std::sqrt(len2 + std::numeric_limits<float>::min());
    const float ok = static_cast<float>(len2 > 0.0f);
    ux[k] = ok * (nx * inv);
    uy[k] = ok * (ny * inv);
    uz[k] = ok * (nz * inv) + (1.0f - ok);
  }
}

void interleave(const PatchScratch& s, int count, const int* order, Vec3f origin, Point3* positions, Point3* normals) {
  for (int k = 0; k < count; ++k) {
    const int at = order ? order[k] : k;
    positions[at] = {origin.x + s.px[k], origin.y + s.py[k], origin.z + s.pz[k]};
    normals[at] = {s.ux[k], s.uy[k], s.uz[k]};
  }
}

}  // namespace

// Float, relative to the patch origin p*_0: what the fast evaluation works in.
PatchControl<float> local_control(const Vec3f* r) {
  PatchControl<float> c;
  const Vec3f origin = r[record_index(0, kP)];
  for (int i = 0; i < 4; ++i) {
    const Vec3f shift = r[record_index(i, kP)] - origin;
    c.v[i] = r[record_index(i, kV)] + shift;
    c.t0[i] = r[record_index(i, kT0)] + shift;
    c.t1[i] = r[record_index(i, kT1)] + shift;
    for (int k = 0; k < 3; ++k) c.x[i][k] = r[record_index(i, RecordEntry(kX0 + k))];
  }
  return c;
}

CpatchPieces expand_cpatch(const Vec3f* record) { return expand(local_control(record)); }

int cpatch_piece(int i, int j, int rate) {
  const int m = rate - 1;
  if (j <= i && j <= m - i) return 0;
  if (i >= j && i >= m - j) return 1;
  if (j >= i && j >= m - i) return 2;
  return 3;
}

SampleGrid::SampleGrid(int rate) : rate_(rate) {
  build_cubic();
  build_quartic();
}

void SampleGrid::build_cubic() {
  cubic_.assign(4 * rate_, 0.0f);
  cubic_du_.assign(4 * rate_, 0.0f);
  for (int i = 0; i < rate_; ++i) {
    const double u = static_cast<double>(i) / (rate_ - 1);
    for (int k = 0; k < 4; ++k) {
      cubic_[k * rate_ + i] = static_cast<float>(cubic_bernstein(k, u));
      cubic_du_[k * rate_ + i] = static_cast<float>(cubic_bernstein_du(k, u));
    }
  }
}

void SampleGrid::build_quartic() {
  const int count = samples();
  piece_order_.clear();
  for (int piece = 0; piece < 4; ++piece) {
    piece_begin_[piece] = static_cast<int>(piece_order_.size());
    for (int s = 0; s < count; ++s)
      if (cpatch_piece(s % rate_, s / rate_, rate_) == piece) piece_order_.push_back(s);
  }
  piece_begin_[4] = count;
  quartic_.assign(kQuarticPoints * count, 0.0f);
  quartic_du_.assign(kQuarticPoints * count, 0.0f);
  quartic_dv_.assign(kQuarticPoints * count, 0.0f);
  for (int piece = 0; piece < 4; ++piece)
    for (int k = piece_begin_[piece]; k < piece_begin_[piece + 1]; ++k) {
      const int s = piece_order_[k];
      const PieceCoords c = piece_coords(piece, static_cast<double>(s % rate_) / (rate_ - 1),
                                         static_cast<double>(s / rate_) / (rate_ - 1));
      for (int m = 0; m < kQuarticPoints; ++m) {
        double w, wu, wv;
        quartic_basis(m, c, w, wu, wv);
        quartic_[m * count + k] = static_cast<float>(w);
        quartic_du_[m * count + k] = static_cast<float>(wu);
        quartic_dv_[m * count + k] = static_cast<float>(wv);
      }
    }
}

int SampleGrid::side_sample(int side, int m) const {
  const int last = rate_ - 1;
  switch (side) {
    case 0:
      return m;  // v = 0, u increasing
    case 1:
      return m * rate_ + last;  // u = 1, v increasing
    case 2:
      return last * rate_ + (last - m);  // v = 1, u decreasing
    default:
      return (last - m) * rate_;  // u = 0, v decreasing
  }
}

void PatchScratch::resize(int samples) {
  data.assign(9 * static_cast<size_t>(samples), 0.0f);
  float* d = data.data();
  px = d, py = d + samples, pz = d + 2 * samples;
  ux = d + 3 * samples, uy = d + 4 * samples, uz = d + 5 * samples;
  vx = d + 6 * samples, vy = d + 7 * samples, vz = d + 8 * samples;
}

// Tensor-product evaluation, separated: per row j the four column curves C_k(v_j) and their v
// derivatives D_k(v_j), then along the row P = sum B_k(u) C_k, P_u = sum B'_k(u) C_k,
// P_v = sum B_k(u) D_k. The row loop, with the 24 column values held in scalars, vectorises
// across samples.
void evaluate_bicubic(const SampleGrid& grid, const Vec3f* record, PatchScratch& out) {
  Vec3f g[4][4];
  bicubic_control_points(local_control(record), g);
  const int n = grid.rate();
  const float* __restrict b0 = grid.cubic(0);
  const float* __restrict b1 = grid.cubic(1);
  const float* __restrict b2 = grid.cubic(2);
  const float* __restrict b3 = grid.cubic(3);
  const float* __restrict d0 = grid.cubic_du(0);
  const float* __restrict d1 = grid.cubic_du(1);
  const float* __restrict d2 = grid.cubic_du(2);
  const float* __restrict d3 = grid.cubic_du(3);
  for (int j = 0; j < n; ++j) {
    Vec3f c[4], d[4];
    for (int k = 0; k < 4; ++k) {
      c[k] = ((b0[j] * g[k][0] + b1[j] * g[k][1]) + b2[j] * g[k][2]) + b3[j] * g[k][3];
      d[k] = ((d0[j] * g[k][0] + d1[j] * g[k][1]) + d2[j] * g[k][2]) + d3[j] * g[k][3];
    }
    const float c0x = c[0].x, c1x = c[1].x, c2x = c[2].x, c3x = c[3].x;
    const float c0y = c[0].y, c1y = c[1].y, c2y = c[2].y, c3y = c[3].y;
    const float c0z = c[0].z, c1z = c[1].z, c2z = c[2].z, c3z = c[3].z;
    const float e0x = d[0].x, e1x = d[1].x, e2x = d[2].x, e3x = d[3].x;
    const float e0y = d[0].y, e1y = d[1].y, e2y = d[2].y, e3y = d[3].y;
    const float e0z = d[0].z, e1z = d[1].z, e2z = d[2].z, e3z = d[3].z;
    const int row = j * n;
    float* __restrict px = out.px + row;
    float* __restrict py = out.py + row;
    float* __restrict pz = out.pz + row;
    float* __restrict ux = out.ux + row;
    float* __restrict uy = out.uy + row;
    float* __restrict uz = out.uz + row;
    float* __restrict vx = out.vx + row;
    float* __restrict vy = out.vy + row;
    float* __restrict vz = out.vz + row;
#pragma omp simd
    for (int i = 0; i < n; ++i) {
      px[i] = ((b0[i] * c0x + b1[i] * c1x) + b2[i] * c2x) + b3[i] * c3x;
      py[i] = ((b0[i] * c0y + b1[i] * c1y) + b2[i] * c2y) + b3[i] * c3y;
      pz[i] = ((b0[i] * c0z + b1[i] * c1z) + b2[i] * c2z) + b3[i] * c3z;
      ux[i] = ((d0[i] * c0x + d1[i] * c1x) + d2[i] * c2x) + d3[i] * c3x;
      uy[i] = ((d0[i] * c0y + d1[i] * c1y) + d2[i] * c2y) + d3[i] * c3y;
      uz[i] = ((d0[i] * c0z + d1[i] * c1z) + d2[i] * c2z) + d3[i] * c3z;
      vx[i] = ((b0[i] * e0x + b1[i] * e1x) + b2[i] * e2x) + b3[i] * e3x;
      vy[i] = ((b0[i] * e0y + b1[i] * e1y) + b2[i] * e2y) + b3[i] * e3y;
      vz[i] = ((b0[i] * e0z + b1[i] * e1z) + b2[i] * e2z) + b3[i] * e3z;
    }
  }
}

// Per piece: P = sum_m w_m(s) b_m over its 15 quartic Bezier points, likewise for the derivatives,
// with the per-sample weights precomputed; samples are in piece order so each loop runs over a
// contiguous range with the piece's points fixed.
SDB_CPATCH_CLONES
void evaluate_cpatch(const SampleGrid& grid, const Vec3f* record, PatchScratch& out) {
  const CpatchPieces pieces = expand_cpatch(record);
  const int count = grid.samples();
  const float* __restrict w = grid.quartic(0);
  const float* __restrict wu = grid.quartic_du(0);
  const float* __restrict wv = grid.quartic_dv(0);
  float* __restrict px = out.px;
  float* __restrict py = out.py;
  float* __restrict pz = out.pz;
  float* __restrict ux = out.ux;
  float* __restrict uy = out.uy;
  float* __restrict uz = out.uz;
  float* __restrict vx = out.vx;
  float* __restrict vy = out.vy;
  float* __restrict vz = out.vz;
  for (int piece = 0; piece < 4; ++piece) {
    float x[kQuarticPoints], y[kQuarticPoints], z[kQuarticPoints];
    for (int m = 0; m < kQuarticPoints; ++m)
      x[m] = pieces[piece][m].x, y[m] = pieces[piece][m].y, z[m] = pieces[piece][m].z;
#pragma omp simd
    for (int k = grid.piece_begin(piece); k < grid.piece_begin(piece + 1); ++k) {
      float sx = 0, sy = 0, sz = 0, sux = 0, suy = 0, suz = 0, svx = 0, svy = 0, svz = 0;
#pragma GCC unroll 15
      for (int m = 0; m < kQuarticPoints; ++m) {
        const float a = w[m * count + k], b = wu[m * count + k], c = wv[m * count + k];
        sx += a * x[m], sy += a * y[m], sz += a * z[m];
        sux += b * x[m], suy += b * y[m], suz += b * z[m];
        svx += c * x[m], svy += c * y[m], svz += c * z[m];
      }
      px[k] = sx, py[k] = sy, pz[k] = sz;
      ux[k] = sux, uy[k] = suy, uz[k] = suz;
      vx[k] = svx, vy[k] = svy, vz[k] = svz;
    }
  }
}

// Side a -> b is evaluated from its lower-index end L to its higher end H in L's frame:
// p*_L + border_point(v_L, t_{L->H}, t_{H->L} + d, v_H + d), d = p*_H - p*_L, all from per-vertex
// data, so the neighbouring quad, which runs the side the other way, computes the same bits.
void write_border(const SampleGrid& grid, const Vec3f* record, uint8_t forward_sides, Point3* positions) {
  const int n = grid.rate(), last = n - 1;
  const float *w0 = grid.cubic(0), *w1 = grid.cubic(1), *w2 = grid.cubic(2), *w3 = grid.cubic(3);
  // Side k's samples: start + m * step, m = 0..N-1 from corner k.
  const int start[4] = {0, last, n * n - 1, n * last};
  const int step[4] = {1, n, -1, -n};
  for (int side = 0; side < 4; ++side) {
    const int a = side, b = (side + 1) % 4;
    const Vec3f& pa = record[record_index(a, kP)];
    const Vec3f& pb = record[record_index(b, kP)];
    positions[start[side]] = to_point3(pa + record[record_index(a, kV)]);
    const bool forward = (forward_sides >> side) & 1u;
    const Vec3f origin = forward ? pa : pb;
    const Vec3f d = forward ? pb - pa : pa - pb;
    const Vec3f c0 = forward ? record[record_index(a, kV)] : record[record_index(b, kV)];
    const Vec3f c1 = forward ? record[record_index(a, kT0)] : record[record_index(b, kT1)];
    const Vec3f c2 = (forward ? record[record_index(b, kT1)] : record[record_index(a, kT0)]) + d;
    const Vec3f c3 = (forward ? record[record_index(b, kV)] : record[record_index(a, kV)]) + d;
    // Canonical sample c = m (forward) or N-1-m, written at the side's position m.
    int at = start[side] + (forward ? 1 : last - 1) * step[side];
    const int advance = forward ? step[side] : -step[side];
    for (int c = 1; c < last; ++c, at += advance)
      positions[at] = to_point3(origin + border_point(c0, c1, c2, c3, w0[c], w1[c], w2[c], w3[c]));
  }
}

void grid_output_topology(int num_quads, int rate, Tessellation& out) {
  const int per_quad = rate * rate;
  const size_t vertices = static_cast<size_t>(num_quads) * per_quad;
  out.positions.assign(vertices, Point3{});
  out.normals.assign(vertices, Point3{});
  out.coords.resize(vertices);
  out.triangles.clear();
  out.triangles.reserve(static_cast<size_t>(num_quads) * 6 * (rate - 1) * (rate - 1));
  for (int q = 0; q < num_quads; ++q) {
    const uint32_t base = static_cast<uint32_t>(q) * static_cast<uint32_t>(per_quad);
    for (int j = 0; j < rate; ++j)
      for (int i = 0; i < rate; ++i)
        out.coords[base + j * rate + i] = {static_cast<uint32_t>(q), static_cast<float>(i) / static_cast<float>(rate - 1),
                                           static_cast<float>(j) / static_cast<float>(rate - 1)};
    for (int j = 0; j + 1 < rate; ++j)
      for (int i = 0; i + 1 < rate; ++i) {
        const uint32_t a = base + j * rate + i, b = a + 1, c = a + rate + 1, d = a + rate;
        out.triangles.insert(out.triangles.end(), {a, b, c, a, c, d});
      }
  }
}

void evaluate_quad(const SampleGrid& grid, const Vec3f* record, bool is_cpatch, uint8_t forward_sides,
                   PatchScratch& scratch, Point3* positions, Point3* normals) {
  const int count = grid.samples();
  if (is_cpatch)
    evaluate_cpatch(grid, record, scratch);
  else
    evaluate_bicubic(grid, record, scratch);
  normals_in_place(scratch, count);
  interleave(scratch, count, is_cpatch ? grid.piece_order() : nullptr, record[record_index(0, kP)], positions, normals);
  write_border(grid, record, forward_sides, positions);
}

}  // namespace sdb::cpatch
