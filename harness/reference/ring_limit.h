// Exact limits at vertices where Far's limit masks are not exact but the ring's rules repeat from
// level to level (no semi-sharpness left): darts, smooth vertices of valence 2, and creases,
// corners and boundaries of extraordinary valence. They come from the eigenvectors of the ring's
// subdivision matrix, built from Sdc's own refinement masks in double.
#pragma once

#include <opensubdiv/far/topologyLevel.h>
#include <opensubdiv/sdc/options.h>

#include <vector>

namespace sdb {

// Weights on the ring of vertex v of `level`: v, the other ends of its edges, then (Catmull-Clark)
// the vertex opposite v in each face, in Far's order rotated to start at edge and face `start`.
// The position: the dominant left eigenvector, by power iteration. Every fragment that meets v
// builds the same matrix in the same order from the same start, so the weights are bit-identical
// in each. Interior vertices only.
std::vector<double> ring_limit_weights(const OpenSubdiv::Far::TopologyLevel& level, const OpenSubdiv::Sdc::Options& options,
                                       bool catmark, int v, int start);

// The two tangents of the limit surface at v on the side of its face `face` (an index into v's
// faces), as weights on the same ring (start 0), ordered so that their cross product points
// along the face's orientation. They are the left eigenvectors of the two largest eigenvalues
// below 1 whose right eigenvectors move that face's corner: the directions in which the refined
// ring leaves v in that sector. Empty where the matrix has no such pair.
struct RingTangents {
  std::vector<double> first, second;
};
RingTangents ring_limit_tangents(const OpenSubdiv::Far::TopologyLevel& level, const OpenSubdiv::Sdc::Options& options,
                                 bool catmark, int v, int face);

// The vertices the weights above refer to, in their order: v, the other ends of its edges, then
// (Catmull-Clark) the vertex opposite v in each face, rotated to start at edge and face `start`.
std::vector<int> ring_limit_vertices(const OpenSubdiv::Far::TopologyLevel& level, int v, bool catmark, int start);

// The ring's subdivision matrix itself (size x size, row-major, rows the next level's ring in the
// same order, start 0), for the tests' oracle: refining the ring by it a few hundred times shows
// the limit's tangent plane without any eigen-analysis.
std::vector<double> ring_subdivision_matrix(const OpenSubdiv::Far::TopologyLevel& level,
                                            const OpenSubdiv::Sdc::Options& options, bool catmark, int v);

}  // namespace sdb
