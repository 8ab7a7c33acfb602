// LimitEvaluator: OpenSubdiv's limit surface (Catmull-Clark or Loop) at any SurfaceCoord, the
// yardstick every scheme is judged by. Built on Bfr surfaces, one per base face, with the
// irregular-patch approximation level raised so that results near extraordinary vertices are
// exact to the residual stated in harness/reference/README.md.
#pragma once

#include <array>
#include <memory>
#include <utility>

#include "control_mesh.h"
#include "osd_topology.h"
#include "tessellation.h"

namespace sdb {

using Point3d = std::array<double, 3>;

struct LimitSample {
  Point3d position{};
  Point3d du{}, dv{};  // first derivatives in the ptex face's (u, v)
  Point3d normal{};    // unit: du x dv normalised
};

struct LimitAccuracy {
  // Bfr::SurfaceFactory approximation levels for irregular faces (OpenSubdiv allows 1..10).
  int smooth = 8;
  int sharp = 8;
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
