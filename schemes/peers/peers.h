// The peer schemes every paper scheme is measured against, run through the same Scheme interface:
//   osd-uniform    Far uniform refinement to depth k, vertices projected to the limit with
//                  PrimvarRefiner::Limit, normals from the limit tangents (Catmull-Clark);
//   osd-uniform-loop  the same with Loop subdivision, for triangle schemes;
//   osd-bfr        Bfr surfaces evaluated on a rate-N tessellation of every face, border points
//                  shared per edge (Bfr tutorial style);
//   embree-subdiv  Embree's Catmull-Clark subdivision geometry evaluated with rtcInterpolate on
//                  the same rate-N layout (Embree's own limit evaluation, not ray sampling).
// One file per peer; scheme.cpp registers them (README.md).
#pragma once

#include <memory>
#include <vector>

#include "harness/core/scheme.h"

namespace sdb {

std::unique_ptr<Scheme> make_osd_uniform(SubdivisionRule rule);
std::unique_ptr<Scheme> make_osd_bfr();
std::unique_ptr<Scheme> make_embree_subdiv();

// osd-uniform, osd-uniform-loop, osd-bfr, embree-subdiv (in this order).
std::vector<std::unique_ptr<Scheme>> make_peer_schemes();

}  // namespace sdb
