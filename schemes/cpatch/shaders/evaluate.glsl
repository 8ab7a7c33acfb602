// Evaluation of a patch record at grid sample (i, j) of the N x N grid u_i = i / (N - 1), N =
// kRate, with the operations of evaluation.cpp (evaluate_bicubic, evaluate_cpatch,
// normals_in_place, interleave, write_border) in the same order, every result `precise`: positions
// come out bit-identical to the CPU's, on every quad side from both quads (README.md, "Exact
// borders"). Needs record.glsl, buffers.glsl with BINDING_GRID, and kRate (a specialization or
// compile-time constant) declared before inclusion.

// The grid table (vulkan_resources.cpp, grid_table()), in vec4s: (B_0..B_3)(u_i) at i, their
// derivatives at N + i, then for grid sample s = j N + i the c-patch's 15 quartic weights of the
// piece holding s (padded to 16): position at 2 N + 12 s + m / 4, component m mod 4, d/du 4 and
// d/dv 8 vec4s further.
const int kSamples = kRate * kRate;
// An includer may read the table elsewhere, through GRID_LOAD(i) (a vec4).
#ifndef GRID_LOAD
#define GRID_LOAD(i) grid[i]
#endif
vec4 cubic_weights(int i) { return GRID_LOAD(i); }
vec4 cubic_derivatives(int i) { return GRID_LOAD(kRate + i); }
vec4 quartic_weights(int table, int s, int quarter) { return GRID_LOAD(2 * kRate + 12 * s + 4 * table + quarter); }

// patch_control.h PatchControl<float>: the record relative to p*_0.
struct PatchControl {
  vec3 v[4], t0[4], t1[4];
  vec3 x[12];  // x[3 i + k]: interior coefficient k of corner i
};

PatchControl local_control(vec3 record[kRecordSize]) {
  PatchControl c;
  [[unroll]] for (int i = 0; i < 4; ++i) {
    precise vec3 shift = record[record_index(i, kP)] - record[record_index(0, kP)];
    precise vec3 v = record[record_index(i, kV)] + shift;
    precise vec3 t0 = record[record_index(i, kT0)] + shift;
    precise vec3 t1 = record[record_index(i, kT1)] + shift;
    c.v[i] = v;
    c.t0[i] = t0;
    c.t1[i] = t1;
    [[unroll]] for (int k = 0; k < 3; ++k) c.x[3 * i + k] = record[record_index(i, kX0 + k)];
  }
  return c;
}

// ((w0 p0 + w1 p1) + w2 p2) + w3 p3: the order of evaluate_bicubic and border_point.
vec3 cubic_combination(vec4 w, vec3 p0, vec3 p1, vec3 p2, vec3 p3) {
  precise vec3 r = ((w.x * p0 + w.y * p1) + w.z * p2) + w.w * p3;
  return r;
}

struct SurfacePoint {
  vec3 position, du, dv;  // position relative to p*_0
};

// Figure 6's 4 x 4 Bezier points g[4 k + l] (k along u, l along v), separated as the CPU does:
// the column curves at v_j (bicubic_columns), then along the row (bicubic_along_row).
void bicubic_columns(PatchControl c, int j, out vec3 column[4], out vec3 column_dv[4]) {
  vec3 g[16];
  g[0] = c.v[0], g[4] = c.t0[0], g[1] = c.t1[0], g[5] = c.x[0];
  g[12] = c.v[1], g[13] = c.t0[1], g[8] = c.t1[1], g[9] = c.x[3];
  g[15] = c.v[2], g[11] = c.t0[2], g[14] = c.t1[2], g[10] = c.x[6];
  g[3] = c.v[3], g[2] = c.t0[3], g[7] = c.t1[3], g[6] = c.x[9];
  const vec4 bv = cubic_weights(j), dv = cubic_derivatives(j);
  [[unroll]] for (int k = 0; k < 4; ++k) {
    column[k] = cubic_combination(bv, g[4 * k], g[4 * k + 1], g[4 * k + 2], g[4 * k + 3]);
    column_dv[k] = cubic_combination(dv, g[4 * k], g[4 * k + 1], g[4 * k + 2], g[4 * k + 3]);
  }
}

SurfacePoint bicubic_along_row(vec3 column[4], vec3 column_dv[4], int i) {
  const vec4 bu = cubic_weights(i), du = cubic_derivatives(i);
  SurfacePoint p;
  p.position = cubic_combination(bu, column[0], column[1], column[2], column[3]);
  p.du = cubic_combination(du, column[0], column[1], column[2], column[3]);
  p.dv = cubic_combination(bu, column_dv[0], column_dv[1], column_dv[2], column_dv[3]);
  return p;
}

SurfacePoint evaluate_bicubic(PatchControl c, int i, int j) {
  vec3 column[4], column_dv[4];
  bicubic_columns(c, j, column, column_dv);
  return bicubic_along_row(column, column_dv, i);
}

// evaluation.cpp cpatch_piece: which triangular piece holds sample (i, j), decided on integers.
int cpatch_piece(int i, int j) {
  const int m = kRate - 1;
  if (j <= i && j <= m - i) return 0;
  if (i >= j && i >= m - j) return 1;
  if (j >= i && j >= m - i) return 2;
  return 3;
}

vec3 midpoint(vec3 a, vec3 b) {
  precise vec3 r = 0.5 * (a + b);
  return r;
}

vec3 quarter_point(vec3 v, vec3 t) {  // (v + 3 t) / 4, degree raising at a corner
  precise vec3 r = 0.25 * (v + 3.0 * t);
  return r;
}

// patch_control.h expand(): the 15 quartic Bezier points of piece i (equations (3), (4)), in
// kQuarticIndex order.
void piece_points(PatchControl c, int i, out vec3 b[15]) {
  const int n = (i + 1) % 4, p = (i + 3) % 4;
#define PICK_X(corner, k) pick(c.x[k], c.x[3 + (k)], c.x[6 + (k)], c.x[9 + (k)], corner)
#define PICK(array, corner) pick(array[0], array[1], array[2], array[3], corner)
  const vec3 B_i = PICK_X(i, 0), C_i = PICK_X(i, 1), X_i = PICK_X(i, 2);
  const vec3 C_p = PICK_X(p, 1), X_p = PICK_X(p, 2);
  const vec3 B_n = PICK_X(n, 0), X_n = PICK_X(n, 2);
  const vec3 v_i = PICK(c.v, i), v_n = PICK(c.v, n), t0_i = PICK(c.t0, i), t1_i = PICK(c.t1, i);
  const vec3 t0_n = PICK(c.t0, n), t1_n = PICK(c.t1, n);
#undef PICK
#undef PICK_X
  precise vec3 center = 0.25 * (((c.x[2] + c.x[5]) + c.x[8]) + c.x[11]);
  const vec3 b310 = quarter_point(v_i, t0_i);
  const vec3 b130 = quarter_point(v_n, t1_n);
  const vec3 b130_prev = quarter_point(v_i, t1_i);
  const vec3 b310_next = quarter_point(v_n, t0_n);
  b[0] = v_i;
  b[1] = b310;
  b[2] = midpoint(b310, b130_prev);
  b[3] = midpoint(t0_i, t1_n);
  b[4] = B_i;
  b[5] = midpoint(B_i, C_p);
  b[6] = b130;
  b[7] = C_i;
  b[8] = X_i;
  b[9] = midpoint(X_i, X_p);
  b[10] = v_n;
  b[11] = midpoint(b130, b310_next);
  b[12] = midpoint(C_i, B_n);
  b[13] = midpoint(X_i, X_n);
  b[14] = center;
}

// Sum over the piece's 15 points with sample s's tabulated weights, in the CPU's order.
SurfacePoint cpatch_point(vec3 b[15], int s) {
  precise vec3 position = vec3(0.0), du = vec3(0.0), dv = vec3(0.0);
  [[unroll]] for (int m = 0; m < 15; ++m) {
    const int quarter = m / 4, k = m % 4;
    const float w = quartic_weights(0, s, quarter)[k], wu = quartic_weights(1, s, quarter)[k], wv = quartic_weights(2, s, quarter)[k];
    position = position + w * b[m];
    du = du + wu * b[m];
    dv = dv + wv * b[m];
  }
  return SurfacePoint(position, du, dv);
}

SurfacePoint evaluate_cpatch(PatchControl c, int i, int j) {
  vec3 b[15];
  piece_points(c, cpatch_piece(i, j), b);
  return cpatch_point(b, j * kRate + i);
}

// Unit normal du x dv; (0, 0, 1) for a degenerate frame (normals_in_place).
vec3 unit_normal(vec3 du, vec3 dv) {
  precise vec3 n = vec3(du.y * dv.z - du.z * dv.y, du.z * dv.x - du.x * dv.z, du.x * dv.y - du.y * dv.x);
  precise float length2 = n.x * n.x + n.y * n.y + n.z * n.z;
  // + FLT_MIN (1.17549435e-38) keeps the division finite, as on the CPU.
  precise float inverse = 1.0 / sqrt(length2 + 1.17549435e-38);
  // The CPU's branch-free form, to the sign of zero: ok n / |n|, plus 1 - ok on z only.
  const float ok = length2 > 0.0 ? 1.0 : 0.0;
  precise vec3 scaled = ok * (n * inverse);
  precise float z = scaled.z + (1.0 - ok);
  return vec3(scaled.x, scaled.y, z);
}

// write_border: side `side` (corner side -> side + 1) at position m (1..N-2, from corner
// `side`), evaluated from the side's lower-index end in that end's frame, at the canonical
// sample index, so that both quads of the edge write the same bits.
vec3 border_position(vec3 record[kRecordSize], uint forward_sides, int side, int m) {
  const int a = side, b = (side + 1) % 4;
  const bool forward = ((forward_sides >> side) & 1u) != 0u;
  const vec3 pa = CORNER_ENTRY(record, a, kP), pb = CORNER_ENTRY(record, b, kP);
  const vec3 va = CORNER_ENTRY(record, a, kV), vb = CORNER_ENTRY(record, b, kV);
  const vec3 t0a = CORNER_ENTRY(record, a, kT0), t1b = CORNER_ENTRY(record, b, kT1);
  const vec3 origin = forward ? pa : pb;
  precise vec3 d = forward ? pb - pa : pa - pb;
  const vec3 c0 = forward ? va : vb;
  const vec3 c1 = forward ? t0a : t1b;
  precise vec3 c2 = (forward ? t1b : t0a) + d;
  precise vec3 c3 = (forward ? vb : va) + d;
  const int c = forward ? m : kRate - 1 - m;
  precise vec3 p = origin + cubic_combination(cubic_weights(c), c0, c1, c2, c3);
  return p;
}

// Grid sample (i, j): position (absolute) and unit normal. Corners are p* + (v - p*), border
// samples border_position(), interior samples p*_0 + the patch; normals always from the patch.
vec3 sample_position(vec3 record[kRecordSize], uint forward_sides, int i, int j, vec3 patch_position) {
  vec3 position;
  const int last = kRate - 1;
  const bool on_corner = (i == 0 || i == last) && (j == 0 || j == last);
  if (on_corner) {
    const int corner = j == 0 ? (i == 0 ? 0 : 1) : (i == 0 ? 3 : 2);
    precise vec3 p = CORNER_ENTRY(record, corner, kP) + CORNER_ENTRY(record, corner, kV);
    position = p;
  } else if (j == 0) {
    position = border_position(record, forward_sides, 0, i);
  } else if (i == last) {
    position = border_position(record, forward_sides, 1, j);
  } else if (j == last) {
    position = border_position(record, forward_sides, 2, last - i);
  } else if (i == 0) {
    position = border_position(record, forward_sides, 3, last - j);
  } else {
    precise vec3 p = record[record_index(0, kP)] + patch_position;
    position = p;
  }
  return position;
}

void evaluate_sample(vec3 record[kRecordSize], bool is_cpatch, uint forward_sides, int i, int j, out vec3 position,
                     out vec3 normal) {
  const PatchControl c = local_control(record);
  const SurfacePoint s = is_cpatch ? evaluate_cpatch(c, i, j) : evaluate_bicubic(c, i, j);
  normal = unit_normal(s.du, s.dv);
  position = sample_position(record, forward_sides, i, j, s.position);
}
