// A tessellation of every base face at a uniform rate in which mesh vertices and edge points are
// shared between the faces that meet there, and each shared point has one owner face that
// evaluates it. Evaluating each point once makes borders bit-identical, hence watertight — the
// approach of OpenSubdiv's Bfr tessellation tutorials. Used by osd-bfr and embree-subdiv.
#pragma once

#include <opensubdiv/far/topologyRefiner.h>

#include <array>
#include <vector>

#include "harness/core/tessellation.h"
#include "harness/mesh/osd_topology.h"

namespace sdb {

struct SharedLayout {
  Tessellation topology;  // triangles and coords; positions and normals left empty
  // Per base face: the output vertices it evaluates and where, in Bfr's (u,v) of that face.
  struct Owned {
    uint32_t vertex;
    float u, v;
  };
  std::vector<std::vector<Owned>> owned_by_face;
};

// segments: edge segments per face side (the scheme's rate N gives N - 1). Hole faces produce
// no triangles and own no points.
SharedLayout make_shared_layout(const OpenSubdiv::Far::TopologyRefiner& refiner, SubdivisionRule rule, int segments);

}  // namespace sdb
