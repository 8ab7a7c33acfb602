// Tessellation: what every scheme returns, and what validation and benchmarks read.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "harness/core/control_mesh.h"

namespace sdb {

// A point of the reference surface: OpenSubdiv's ptex-style parametrization of the mesh the
// scheme consumed (one (u,v) square per quad, one per triangle for Loop, one per sub-quad of an
// n-gon). `face` is the ptex face index (Far::PtexIndices), which equals the face index on an
// all-quad Catmull-Clark mesh or an all-triangle Loop mesh.
struct SurfaceCoord {
  uint32_t face = 0;
  float u = 0.0f, v = 0.0f;
};

struct Tessellation {
  std::vector<Point3> positions;
  std::vector<Point3> normals;  // unit length
  std::vector<uint32_t> triangles;  // three indices per triangle
  std::vector<SurfaceCoord> coords;  // one per vertex
  // The mesh the coords refer to when the scheme subdivides a control mesh of its own (a geometry
  // image's g0, fitted to the input). Null means: the scheme's input. Validation judges every row
  // against the input's limit surface all the same (by nearest points where the coords are on
  // another mesh); this mesh's limit at the coords is the row's second figure, the scheme's
  // exactness (harness/bench/measure.h, validate_into).
  std::shared_ptr<const ControlMesh> reference;

  size_t num_vertices() const { return positions.size(); }
  size_t num_triangles() const { return triangles.size() / 3; }
};

}  // namespace sdb
