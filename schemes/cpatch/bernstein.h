// Bernstein bases in double precision: the cubic one of the bicubic patches and the quartic
// triangular one of the c-patch's pieces, on the quad's (u, v) square split by its diagonals.
// Used to tabulate the SampleGrid's weights and by the reference evaluation. Internal.
#pragma once

#include "schemes/cpatch/evaluation.h"

namespace sdb::cpatch {

inline double power(double x, int e) {
  double r = 1.0;
  for (int i = 0; i < e; ++i) r *= x;
  return r;
}

inline double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

// Bernstein polynomial of total degree k + l + m at barycentric (a, b, c).
inline double bernstein3(int k, int l, int m, double a, double b, double c) {
  if (k < 0 || l < 0 || m < 0) return 0.0;
  return factorial(k + l + m) / (factorial(k) * factorial(l) * factorial(m)) * power(a, k) * power(b, l) * power(c, m);
}

inline double cubic_bernstein(int k, double u) { return bernstein3(k, 3 - k, 0, u, 1.0 - u, 0.0); }
inline double cubic_bernstein_du(int k, double u) {
  return 3.0 * (bernstein3(k - 1, 3 - k, 0, u, 1.0 - u, 0.0) - bernstein3(k, 2 - k, 0, u, 1.0 - u, 0.0));
}

// A piece's barycentric coordinates (corner i, corner i+1, centre) at (u, v), with their
// (constant) derivatives in u and v.
struct PieceCoords {
  double l[3], du[3], dv[3];
};

inline PieceCoords piece_coords(int piece, double u, double v) {
  static const double corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const double ax = corner[piece][0] - 0.5, ay = corner[piece][1] - 0.5;
  const double bx = corner[(piece + 1) % 4][0] - 0.5, by = corner[(piece + 1) % 4][1] - 0.5;
  // (u, v) - centre = l0 (A - centre) + l1 (B - centre); invert the 2 x 2 system.
  const double det = ax * by - bx * ay;
  const double i00 = by / det, i01 = -bx / det, i10 = -ay / det, i11 = ax / det;
  const double x = u - 0.5, y = v - 0.5;
  PieceCoords p;
  p.l[0] = i00 * x + i01 * y;
  p.l[1] = i10 * x + i11 * y;
  p.l[2] = 1.0 - p.l[0] - p.l[1];
  p.du[0] = i00, p.du[1] = i10, p.du[2] = -(i00 + i10);
  p.dv[0] = i01, p.dv[1] = i11, p.dv[2] = -(i01 + i11);
  return p;
}

// Quartic basis function m of kQuarticIndex and its u, v derivatives at piece coordinates c.
inline void quartic_basis(int m, const PieceCoords& c, double& w, double& wu, double& wv) {
  const auto [k, l, n] = kQuarticIndex[m];
  const double* x = c.l;
  w = bernstein3(k, l, n, x[0], x[1], x[2]);
  const double d0 = 4.0 * bernstein3(k - 1, l, n, x[0], x[1], x[2]);
  const double d1 = 4.0 * bernstein3(k, l - 1, n, x[0], x[1], x[2]);
  const double d2 = 4.0 * bernstein3(k, l, n - 1, x[0], x[1], x[2]);
  wu = c.du[0] * d0 + c.du[1] * d1 + c.du[2] * d2;
  wv = c.dv[0] * d0 + c.dv[1] * d1 + c.dv[2] * d2;
}

inline int piece_at(double u, double v) {
  if (v <= u && v <= 1.0 - u) return 0;
  if (u >= v && u >= 1.0 - v) return 1;
  if (v >= u && v >= 1.0 - u) return 2;
  return 3;
}

}  // namespace sdb::cpatch
