// The peer schemes every paper scheme is measured against, run through the same Scheme interface:
//   osd-uniform    Far uniform refinement to depth k, vertices projected to the limit with
//                  PrimvarRefiner::Limit, normals from the limit tangents (Catmull-Clark);
//   osd-uniform-loop  the same with Loop subdivision, for triangle schemes;
//   osd-bfr        Bfr surfaces evaluated on a rate-N tessellation of every face, border points
//                  shared per edge (Bfr tutorial style);
//   embree-subdiv  Embree's Catmull-Clark subdivision geometry evaluated with rtcInterpolate on
//                  the same rate-N layout (Embree's own limit evaluation, not ray sampling).
#pragma once

#include <memory>
#include <vector>

#include "scheme.h"

namespace sdb {

std::vector<std::unique_ptr<Scheme>> make_peer_schemes();

}  // namespace sdb
