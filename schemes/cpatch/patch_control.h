// PatchControl: a patch record's control data (corner points, interior coefficients) in one
// frame, shared by the evaluation routines. Internal to schemes/cpatch.
#pragma once

#include "conversion.h"
#include "vec3.h"

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

// Float, relative to the patch origin p*_0: what the fast evaluation works in.
PatchControl<float> local_control(const Vec3f* record);
// Double, absolute: for the reference evaluation.
PatchControl<double> absolute_control(const Vec3f* record);

}  // namespace sdb::cpatch
