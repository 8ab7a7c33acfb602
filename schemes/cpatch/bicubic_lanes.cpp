// evaluate_bicubic_lanes: eight ordinary quads per call, one per SIMD lane.
//
// Every lane performs exactly the floating-point operations of evaluate_bicubic,
// normals_in_place, interleave and write_border for its quad, in the same order and without fused
// multiply-adds (-ffp-contract=off), so its output is bit-identical to evaluate_quad's whichever
// instruction set runs it. What changes is the instruction count per sample: the grid weights are
// shared by all lanes (broadcast), there is no remainder at row ends, and the results are turned
// into packed float3 by in-register transposes. Built twice through target_clones, for AVX2
// (eight floats per register) and for the x86-64 baseline (two SSE registers per vector), picked
// at load time.
#include <cmath>
#include <limits>

#include "schemes/cpatch/conversion.h"
#include "schemes/cpatch/evaluation.h"

namespace sdb::cpatch {
namespace {

static_assert(kLanes == 8, "the transposes below are written for eight lanes");
using Lanes = float __attribute__((vector_size(kLanes * sizeof(float))));
using LaneMask = int __attribute__((vector_size(kLanes * sizeof(int))));
using Quad = float __attribute__((vector_size(4 * sizeof(float))));

// Helpers take and return vectors by value only when inlined into the clones.
#define SDB_LANES inline __attribute__((always_inline))

struct Vec3Lanes {
  Lanes x, y, z;
};

SDB_LANES Lanes broadcast(float s) { return Lanes{} + s; }
SDB_LANES Vec3Lanes add(const Vec3Lanes& a, const Vec3Lanes& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
SDB_LANES Vec3Lanes scale(Lanes s, const Vec3Lanes& a) { return {s * a.x, s * a.y, s * a.z}; }
// ((w0 p0 + w1 p1) + w2 p2) + w3 p3: the order of evaluate_bicubic and border_point.
SDB_LANES Vec3Lanes combine(Lanes w0, Lanes w1, Lanes w2, Lanes w3, const Vec3Lanes* p) {
  return add(add(add(scale(w0, p[0]), scale(w1, p[1])), scale(w2, p[2])), scale(w3, p[3]));
}
SDB_LANES Lanes lane_sqrt(Lanes a) {
  Lanes r;
  for (int l = 0; l < kLanes; ++l) r[l] = std::sqrt(a[l]);  // one vector sqrt: -fno-math-errno
  return r;
}

// Lane l's (x, y, z) to outputs[l][at]. Sweep stores write 16 bytes, running one float into
// entry at + 1, which a caller sweeping `at` upwards overwrites next; Exact stores write 12 bytes
// (the last entry of a quad, and border entries).
enum class Store { Sweep, Exact };
template <Store kind>
SDB_LANES void store_transposed(Lanes x, Lanes y, Lanes z, Point3* const outputs[kLanes], int at) {
  // Within each 128-bit half: (x_l, y_l, z_l, z_l) for l = 0..3 | 4..7.
  const Lanes xy_lo = __builtin_shufflevector(x, y, 0, 8, 1, 9, 4, 12, 5, 13);
  const Lanes xy_hi = __builtin_shufflevector(x, y, 2, 10, 3, 11, 6, 14, 7, 15);
  const Lanes zz_lo = __builtin_shufflevector(z, z, 0, 8, 1, 9, 4, 12, 5, 13);
  const Lanes zz_hi = __builtin_shufflevector(z, z, 2, 10, 3, 11, 6, 14, 7, 15);
  const Lanes rows[4] = {__builtin_shufflevector(xy_lo, zz_lo, 0, 1, 8, 9, 4, 5, 12, 13),
                         __builtin_shufflevector(xy_lo, zz_lo, 2, 3, 10, 11, 6, 7, 14, 15),
                         __builtin_shufflevector(xy_hi, zz_hi, 0, 1, 8, 9, 4, 5, 12, 13),
                         __builtin_shufflevector(xy_hi, zz_hi, 2, 3, 10, 11, 6, 7, 14, 15)};
  constexpr size_t bytes = kind == Store::Sweep ? sizeof(Quad) : sizeof(Point3);
  for (int q = 0; q < 4; ++q) {
    const Quad low = __builtin_shufflevector(rows[q], rows[q], 0, 1, 2, 3);
    const Quad high = __builtin_shufflevector(rows[q], rows[q], 4, 5, 6, 7);
    __builtin_memcpy(&outputs[q][at], &low, bytes);
    __builtin_memcpy(&outputs[q + 4][at], &high, bytes);
  }
}

// Figure 6's data, one lane per quad, corner i: p*_i and v^i, t_0^i, t_1^i, f^i relative to p*_i
// (as VertexPoints holds them).
struct LaneRecords {
  Vec3Lanes p[4], v[4], t0[4], t1[4], f[4];
};

SDB_LANES void load_lane(Vec3Lanes& out, int l, const Vec3f& value) {
  out.x[l] = value.x, out.y[l] = value.y, out.z[l] = value.z;
}

SDB_LANES LaneRecords gather(const BicubicLaneSource& source) {
  LaneRecords r;
  const VertexPoints& points = *source.points;
  for (int l = 0; l < kLanes; ++l)
    for (int i = 0; i < 4; ++i) {
      const QuadCorner& c = source.corners[l][i];
      load_lane(r.p[i], l, source.positions[c.vertex]);
      load_lane(r.v[i], l, points.limit[c.vertex]);
      load_lane(r.t0[i], l, points.tangent[c.sector_slot]);
      load_lane(r.t1[i], l, points.tangent[c.prev_edge_slot]);
      load_lane(r.f[i], l, points.face[c.sector_slot]);
    }
  return r;
}

SDB_LANES Vec3Lanes sub(const Vec3Lanes& a, const Vec3Lanes& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
SDB_LANES Vec3Lanes select(LaneMask m, const Vec3Lanes& a, const Vec3Lanes& b) {
  return {m ? a.x : b.x, m ? a.y : b.y, m ? a.z : b.z};
}

struct LaneInput {
  Vec3Lanes g[4][4];  // g[k][l]: Bezier net column k (u index), row l (v index), relative to p*_0
  Lanes origin_x, origin_y, origin_z;
};

// build_bicubic + local_control + bicubic_control_points, lane by lane the same operations.
SDB_LANES LaneInput bicubic_lanes_input(const LaneRecords& r) {
  Vec3Lanes v[4], t0[4], t1[4], f[4];
  for (int i = 0; i < 4; ++i) {
    const Vec3Lanes shift = sub(r.p[i], r.p[0]);
    v[i] = add(r.v[i], shift), t0[i] = add(r.t0[i], shift), t1[i] = add(r.t1[i], shift), f[i] = add(r.f[i], shift);
  }
  LaneInput in;
  auto& g = in.g;
  g[0][0] = v[0], g[1][0] = t0[0], g[0][1] = t1[0], g[1][1] = f[0];
  g[3][0] = v[1], g[3][1] = t0[1], g[2][0] = t1[1], g[2][1] = f[1];
  g[3][3] = v[2], g[2][3] = t0[2], g[3][2] = t1[2], g[2][2] = f[2];
  g[0][3] = v[3], g[0][2] = t0[3], g[1][3] = t1[3], g[1][2] = f[3];
  in.origin_x = r.p[0].x, in.origin_y = r.p[0].y, in.origin_z = r.p[0].z;
  return in;
}

// One sample of evaluate_bicubic + normals_in_place + interleave for all lanes. Border samples
// skip the position (border_lanes writes it); a Sweep store's spill into the next entry is
// overwritten by the next sample or, at a row's end, by border_lanes.
template <bool interior>
SDB_LANES void sample_lanes(const LaneInput& in, const Lanes bu[4], const Lanes du[4], const Vec3Lanes c[4],
                            const Vec3Lanes e[4], int s, bool last_sample, Point3* const positions[kLanes],
                            Point3* const normals[kLanes]) {
  const Lanes one = broadcast(1.0f), tiny = broadcast(std::numeric_limits<float>::min());
  if constexpr (interior) {
    const Vec3Lanes p = combine(bu[0], bu[1], bu[2], bu[3], c);
    store_transposed<Store::Sweep>(in.origin_x + p.x, in.origin_y + p.y, in.origin_z + p.z, positions, s);
  }
  const Vec3Lanes u = combine(du[0], du[1], du[2], du[3], c);
  const Vec3Lanes v = combine(bu[0], bu[1], bu[2], bu[3], e);
  const Lanes nx = u.y * v.z - u.z * v.y;
  const Lanes ny = u.z * v.x - u.x * v.z;
  const Lanes nz = u.x * v.y - u.y * v.x;
  const Lanes len2 = nx * nx + ny * ny + nz * nz;
  const Lanes inv = one / lane_sqrt(len2 + tiny);
  const Lanes ok = reinterpret_cast<Lanes>((len2 > Lanes{}) & reinterpret_cast<LaneMask>(one));
  const Lanes rx = ok * (nx * inv), ry = ok * (ny * inv), rz = ok * (nz * inv) + (one - ok);
  if (last_sample)
    store_transposed<Store::Exact>(rx, ry, rz, normals, s);
  else
    store_transposed<Store::Sweep>(rx, ry, rz, normals, s);
}

// evaluate_bicubic + normals_in_place + interleave, row by row.
SDB_LANES void evaluate_lanes(const SampleGrid& grid, const LaneInput& in, Point3* const positions[kLanes],
                              Point3* const normals[kLanes]) {
  const int n = grid.rate(), last = n - 1;
  const float* b[4] = {grid.cubic(0), grid.cubic(1), grid.cubic(2), grid.cubic(3)};
  const float* d[4] = {grid.cubic_du(0), grid.cubic_du(1), grid.cubic_du(2), grid.cubic_du(3)};
  for (int j = 0; j < n; ++j) {
    Vec3Lanes c[4], e[4];  // column curves C_k(v_j) and their v derivatives D_k(v_j)
    for (int k = 0; k < 4; ++k) {
      c[k] = combine(broadcast(b[0][j]), broadcast(b[1][j]), broadcast(b[2][j]), broadcast(b[3][j]), in.g[k]);
      e[k] = combine(broadcast(d[0][j]), broadcast(d[1][j]), broadcast(d[2][j]), broadcast(d[3][j]), in.g[k]);
    }
    const bool border_row = j == 0 || j == last;
    for (int i = 0; i < n; ++i) {
      const Lanes bu[4] = {broadcast(b[0][i]), broadcast(b[1][i]), broadcast(b[2][i]), broadcast(b[3][i])};
      const Lanes du[4] = {broadcast(d[0][i]), broadcast(d[1][i]), broadcast(d[2][i]), broadcast(d[3][i])};
      const int s = j * n + i;
      if (border_row || i == 0 || i == last)
        sample_lanes<false>(in, bu, du, c, e, s, s == n * n - 1, positions, normals);
      else
        sample_lanes<true>(in, bu, du, c, e, s, false, positions, normals);
    }
  }
}

// write_border for all lanes, each lane doing its operations: the lanes share the sample
// positions along a side; a lane that runs the side backwards (its canonical direction is the
// other one) selects the other end's data and the weights of canonical index N-1-m instead of m.
SDB_LANES void border_lanes(const SampleGrid& grid, const LaneRecords& r, const uint8_t forward_sides[kLanes],
                            Point3* const positions[kLanes]) {
  const int n = grid.rate(), last = n - 1;
  const float* w[4] = {grid.cubic(0), grid.cubic(1), grid.cubic(2), grid.cubic(3)};
  const int start[4] = {0, last, n * n - 1, n * last};
  const int step[4] = {1, n, -1, -n};
  for (int side = 0; side < 4; ++side) {
    const int a = side, b = (side + 1) % 4;
    LaneMask forward;
    for (int l = 0; l < kLanes; ++l) forward[l] = ((forward_sides[l] >> side) & 1u) ? -1 : 0;
    const Vec3Lanes corner = add(r.p[a], r.v[a]);
    store_transposed<Store::Exact>(corner.x, corner.y, corner.z, positions, start[side]);
    const Vec3Lanes origin = select(forward, r.p[a], r.p[b]);
    const Vec3Lanes delta = select(forward, sub(r.p[b], r.p[a]), sub(r.p[a], r.p[b]));
    const Vec3Lanes c[4] = {select(forward, r.v[a], r.v[b]), select(forward, r.t0[a], r.t1[b]),
                            add(select(forward, r.t1[b], r.t0[a]), delta), add(select(forward, r.v[b], r.v[a]), delta)};
    for (int m = 1; m < last; ++m) {
      Lanes weight[4];
      for (int k = 0; k < 4; ++k) weight[k] = forward ? broadcast(w[k][m]) : broadcast(w[k][last - m]);
      const Vec3Lanes p = combine(weight[0], weight[1], weight[2], weight[3], c);
      store_transposed<Store::Exact>(origin.x + p.x, origin.y + p.y, origin.z + p.z, positions,
                                     start[side] + m * step[side]);
    }
  }
}

}  // namespace

SDB_CPATCH_CLONES
void evaluate_bicubic_lanes(const SampleGrid& grid, const BicubicLaneSource& source,
                            const uint8_t forward_sides[kLanes], Point3* const positions[kLanes],
                            Point3* const normals[kLanes]) {
  const LaneRecords r = gather(source);
  evaluate_lanes(grid, bicubic_lanes_input(r), positions, normals);
  border_lanes(grid, r, forward_sides, positions);
}

}  // namespace sdb::cpatch
