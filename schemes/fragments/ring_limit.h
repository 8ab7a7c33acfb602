// The exact limit position at a vertex where Far's limit masks are not exact but the ring's rules
// repeat from level to level (a dart, whose sharp edge is infinitely sharp; a smooth vertex of
// valence 2): the dominant left eigenvector of the ring's subdivision matrix, by power iteration
// in double, the matrix made of Sdc's own refinement masks.
#pragma once

#include <opensubdiv/far/topologyLevel.h>
#include <opensubdiv/sdc/options.h>

#include <vector>

namespace sdb::fragments {

// Weights on the ring of vertex v of `level`: v, the other ends of its edges, then (Catmull-Clark)
// the vertex opposite v in each face, in Far's order rotated to start at edge and face `start`.
// Every fragment that meets v builds the same matrix in the same order from the same start, so
// the weights are bit-identical in each.
std::vector<double> ring_limit_weights(const OpenSubdiv::Far::TopologyLevel& level, const OpenSubdiv::Sdc::Options& options,
                                       bool catmark, int v, int start);

}  // namespace sdb::fragments
