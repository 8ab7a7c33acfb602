// PatchControl: a patch record's control data (corner points, interior coefficients) in one
// frame, shared by the evaluation routines. Internal to schemes/cpatch.
#pragma once

#include <array>

#include "schemes/cpatch/conversion.h"
#include "schemes/cpatch/evaluation.h"
#include "schemes/cpatch/vec3.h"

namespace sdb::cpatch {

// A record's control data in one frame: the corner points and interior coefficients.
template <class T>
struct PatchControl {
  Vec3<T> v[4], t0[4], t1[4], x[4][3];
};

// Figure 6: the 4 x 4 Bezier points g[k][l] (k along u, l along v) of an ordinary quad.
template <class T>
void bicubic_control_points(const PatchControl<T>& c, Vec3<T> g[4][4]) {
  g[0][0] = c.v[0], g[1][0] = c.t0[0], g[0][1] = c.t1[0], g[1][1] = c.x[0][0];
  g[3][0] = c.v[1], g[3][1] = c.t0[1], g[2][0] = c.t1[1], g[2][1] = c.x[1][0];
  g[3][3] = c.v[2], g[2][3] = c.t0[2], g[3][2] = c.t1[2], g[2][2] = c.x[2][0];
  g[0][3] = c.v[3], g[0][2] = c.t0[3], g[1][3] = c.t1[3], g[1][2] = c.x[3][0];
}

// Equations (4) (boundary points by degree raising) and (3) (interior points implied by C1
// continuity between the pieces), in kQuarticIndex order.
template <class T>
std::array<std::array<Vec3<T>, kQuarticPoints>, 4> expand(const PatchControl<T>& c) {
  auto B = [&](int i) { return c.x[(i + 4) % 4][0]; };  // b211
  auto C = [&](int i) { return c.x[(i + 4) % 4][1]; };  // b121
  auto X = [&](int i) { return c.x[(i + 4) % 4][2]; };  // b112
  const T half = 0.5, quarter = 0.25, three = 3;
  const Vec3<T> center = quarter * (((X(0) + X(1)) + X(2)) + X(3));
  std::array<std::array<Vec3<T>, kQuarticPoints>, 4> pieces;
  for (int i = 0; i < 4; ++i) {
    const int n = (i + 1) % 4;
    const Vec3<T> b310 = quarter * (c.v[i] + three * c.t0[i]);
    const Vec3<T> b130 = quarter * (c.v[n] + three * c.t1[n]);
    const Vec3<T> b130_prev = quarter * (c.v[i] + three * c.t1[i]);  // b^{i-1}_130
    const Vec3<T> b310_next = quarter * (c.v[n] + three * c.t0[n]);  // b^{i+1}_310
    pieces[i] = {c.v[i],
                 b310,
                 half * (b310 + b130_prev),   // b301
                 half * (c.t0[i] + c.t1[n]),  // b220
                 B(i),                        // b211
                 half * (B(i) + C(i - 1)),    // b202
                 b130,                        // b130
                 C(i),                        // b121
                 X(i),                        // b112
                 half * (X(i) + X(i - 1)),    // b103
                 c.v[n],                      // b040
                 half * (b130 + b310_next),   // b031
                 half * (C(i) + B(i + 1)),    // b022
                 half * (X(i) + X(i + 1)),    // b013
                 center};                     // b004
  }
  return pieces;
}

// Float, relative to the patch origin p*_0: what the fast evaluation works in.
PatchControl<float> local_control(const Vec3f* record);
// Double, absolute: for the reference evaluation.
PatchControl<double> absolute_control(const Vec3f* record);

}  // namespace sdb::cpatch
