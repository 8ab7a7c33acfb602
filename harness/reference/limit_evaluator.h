// LimitEvaluator: OpenSubdiv's limit surface (Catmull-Clark or Loop) at any SurfaceCoord, the
// yardstick every scheme is judged by. Built on Bfr surfaces, one per base face, with the
// irregular-patch approximation level raised so that results near extraordinary vertices are
// exact to the residual stated in harness/reference/README.md.
#pragma once

#include <array>
#include <memory>
#include <utility>

#include "harness/core/control_mesh.h"
#include "harness/core/tessellation.h"
#include "harness/mesh/osd_topology.h"

namespace sdb {

using Point3d = std::array<double, 3>;

struct LimitSample {
  Point3d position{};
  Point3d du{}, dv{};  // first derivatives in the ptex face's (u, v)
  Point3d normal{};    // unit: du x dv normalised
};

// Bfr approximates an irregular face by refining towards its extraordinary corner to this level.
// Measured (reference_test, README): at level L the result is exact to double precision at the
// corner itself and wherever the ptex distance from it is at least 2^-(L-1); the residual lives
// inside that radius. Level 10 (OpenSubdiv's maximum) is thus exact at every sample of rate
// N <= 257 or depth <= 8, and within 3.3e-4 of the bounding-box diagonal inside 2^-9 of a
// valence-64 vertex (the worst case measured).
struct LimitAccuracy {
  int smooth = 10;
  int sharp = 10;
};

class LimitEvaluator {
 public:
  LimitEvaluator(const ControlMesh& mesh, SubdivisionRule rule, LimitAccuracy accuracy = {});
  ~LimitEvaluator();
  LimitEvaluator(const LimitEvaluator&) = delete;
  LimitEvaluator& operator=(const LimitEvaluator&) = delete;

  int num_ptex_faces() const;
  // {base face, sub-face}: sub-face is 0 for quads (Catmull-Clark) and triangles (Loop), k for
  // the k-th corner sub-quad of an n-gon.
  std::pair<int, int> base_face(int ptex_face) const;
  // First ptex face of a base face (Far::PtexIndices).
  int first_ptex_face(int base_face) const;
  // False for holes and faces with no limit surface.
  bool has_limit(int ptex_face) const;
  // Thread-safe.
  LimitSample evaluate(SurfaceCoord c) const;
  // Mean edge length of the base face's control polygon: the "local quad size" deviation is
  // expressed in (the c-patch paper's Figure 12 measure).
  double local_size(int ptex_face) const;
  const ControlMesh& mesh() const;
  SubdivisionRule rule() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sdb
