// Reference evaluation of patch records in double precision, directly from the Bernstein bases:
// independent of the SampleGrid's tables, the piece order and the float paths, for tests.
#include "schemes/cpatch/bernstein.h"
#include "schemes/cpatch/evaluation.h"
#include "schemes/cpatch/patch_control.h"

namespace sdb::cpatch {
namespace {

template <class T>
Vec3<T> as(Vec3f p) {
  return {T(p.x), T(p.y), T(p.z)};
}

void add_scaled(std::array<double, 3>& acc, double w, const Vec3d& p) {
  acc[0] += w * p.x;
  acc[1] += w * p.y;
  acc[2] += w * p.z;
}

}  // namespace

// Double, absolute: for the reference evaluation.
PatchControl<double> absolute_control(const Vec3f* r) {
  PatchControl<double> c;
  const Vec3d origin = as<double>(r[record_index(0, kP)]);
  for (int i = 0; i < 4; ++i) {
    const Vec3d corner = as<double>(r[record_index(i, kP)]);
    c.v[i] = corner + as<double>(r[record_index(i, kV)]);
    c.t0[i] = corner + as<double>(r[record_index(i, kT0)]);
    c.t1[i] = corner + as<double>(r[record_index(i, kT1)]);
    for (int k = 0; k < 3; ++k) c.x[i][k] = origin + as<double>(r[record_index(i, RecordEntry(kX0 + k))]);
  }
  return c;
}

PatchPoint bicubic_at(const Vec3f* record, double u, double v) {
  Vec3d g[4][4];
  bicubic_control_points(absolute_control(record), g);
  PatchPoint out;
  for (int k = 0; k < 4; ++k)
    for (int l = 0; l < 4; ++l) {
      add_scaled(out.position, cubic_bernstein(k, u) * cubic_bernstein(l, v), g[k][l]);
      add_scaled(out.du, cubic_bernstein_du(k, u) * cubic_bernstein(l, v), g[k][l]);
      add_scaled(out.dv, cubic_bernstein(k, u) * cubic_bernstein_du(l, v), g[k][l]);
    }
  return out;
}

PatchPoint cpatch_at(const Vec3f* record, double u, double v) {
  const auto pieces = expand(absolute_control(record));
  const int piece = piece_at(u, v);
  const PieceCoords c = piece_coords(piece, u, v);
  PatchPoint out;
  for (int m = 0; m < kQuarticPoints; ++m) {
    double w, wu, wv;
    quartic_basis(m, c, w, wu, wv);
    add_scaled(out.position, w, pieces[piece][m]);
    add_scaled(out.du, wu, pieces[piece][m]);
    add_scaled(out.dv, wv, pieces[piece][m]);
  }
  return out;
}

}  // namespace sdb::cpatch
