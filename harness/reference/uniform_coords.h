// SurfaceCoords of the vertices of a uniformly refined mesh: which ptex face and (u,v) of the
// base mesh each level-k vertex lies at. Needed by every recursive scheme (osd-uniform, mesh
// fragments, MiPGH) to compare with the reference at the same surface point.
#pragma once

#include <opensubdiv/far/topologyRefiner.h>

#include <vector>

#include "harness/core/tessellation.h"
#include "harness/mesh/osd_topology.h"

namespace sdb {

// One SurfaceCoord per vertex of level `level` (refiner refined uniformly at least that far).
// Vertices on ptex borders get the coord of one of their faces.
std::vector<SurfaceCoord> uniform_vertex_coords(const OpenSubdiv::Far::TopologyRefiner& refiner,
                                                SubdivisionRule rule, int level);

// One SurfaceCoord per corner of every face of level `level`, in face-vertex order (face f's
// corners start at the sum of the earlier faces' sizes): a vertex on a ptex border has one per
// face around it, in that face's parametrization (its side).
std::vector<SurfaceCoord> uniform_face_corner_coords(const OpenSubdiv::Far::TopologyRefiner& refiner,
                                                     SubdivisionRule rule, int level);

// The triangles of level `level`: every face fanned from its first vertex, holes left out.
std::vector<uint32_t> uniform_triangles(const OpenSubdiv::Far::TopologyRefiner& refiner, int level);

}  // namespace sdb
