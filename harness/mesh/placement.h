// Where a run's mesh lies and how large it is, taken out of what is judged: the harness hands every
// scheme and the reference the mesh centred on its bounding box and scaled to a diagonal near 1,
// so that a mesh scaled by 1e10 or 1e-30, or moved 1e7 away, gives the verdicts of the unit one
// (float cannot hold the squares of the first two, nor the detail of the third, in any scheme's
// kernel). Geometry no verdict can be made on is refused here, naming what is degenerate.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "harness/core/control_mesh.h"

namespace sdb {

// The bounds of the vertices the faces use: the geometry the surface is made of. An unused vertex
// far away must not widen the diagonal deviations are stated against.
Bounds used_bounds(const ControlMesh& mesh);

// placed = (original - centre) * scale; scale is a power of two, so that it is exact in float.
struct Placement {
  std::array<double, 3> centre{0, 0, 0};
  double scale = 1;
  Point3 original(const Point3& placed) const;
};

// What makes the mesh's geometry impossible to judge, with the file and line where one face says
// it: every used vertex at one point, all on one line, every face of zero area, or a face whose
// distinct vertices all lie at one point (it has no size to state a deviation against). nullopt
// when the geometry can be judged. Faces that repeat one vertex (OpenSubdiv's regression shapes
// have them) are topology, reported by MeshFacts, not degenerate geometry.
std::optional<std::string> degenerate_geometry(const ControlMesh& mesh);

// The placement a mesh is judged in: its used bounds' centre at the origin, its diagonal in [0.7, 1.4).
Placement placement_of(const ControlMesh& mesh);

// The mesh as every run takes it: placed by placement_of. Throws InputError (the file, and the
// line where a face is to blame) when degenerate_geometry finds the geometry unjudgeable.
ControlMesh placed_mesh(const ControlMesh& mesh);

}  // namespace sdb
