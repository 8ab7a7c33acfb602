// The limit masks of a vertex where Far's are not the limit, on one face's side: the yardstick's
// rule (harness/reference/vertex_limit.h) in the form of weights on the vertex's ring, so that the
// frame applies them to the level's points as it applies Far's.
//
// Far's limit masks (Sdc::Scheme::ComputeVertexLimitMask) are the limit at smooth vertices of
// valence 3 and more, at regular creases and at a boundary corner of one face, and nowhere
// sharpness is left (far_tangent_masks_exact, harness/mesh/osd_topology.h). Elsewhere they miss:
// a dart's tangents by 55 degrees (catmark_dart_edgeonly), a corner's several sides by up to 87
// (catmark_cube_creases1: Far's tangents are those of the side its ring starts in), a semi-sharp
// crease left at the depth by 63 (catmark_chaikin0 at depth 1). Here:
//   - while a semi-sharp edge or corner is left at the vertex, its ring is refined by Far, one
//     level at a time (its rules read the ring alone), and the level's matrix composed;
//   - once its rules repeat, the position is Far's mask (a dart's or a smooth valence-2
//     vertex's: the dominant eigenvector of the ring's matrix), the tangents Far's where they are
//     the limit and the ring has one side, the two crease curves' ends where the face lies
//     between two infinitely sharp edges, and elsewhere the eigenvectors of the ring's matrix on
//     the side of the face (harness/reference/ring_limit.h), scaled to weights of 1 at most.
// The composed masks are weights on the given ring: a limit is linear in its points.
#pragma once

#include <opensubdiv/sdc/options.h>

#include <vector>

#include "harness/core/control_mesh.h"

namespace sdb::refined {

// A vertex's ring as a disk of its own: slot 0 the vertex, 1 + i the far end of edge i
// (counter-clockwise; at a boundary edge 0 is the leading boundary edge and there is one edge
// more than faces), and under Catmull-Clark 1 + edges + i the vertex opposite it in face i, which
// lies between edges i and i + 1.
struct RingDisk {
  int edges = 0, faces = 0;
  std::vector<float> edge_sharpness;  // per edge (boundary edges: infinitely sharp)
  float vertex_sharpness = 0;
  int side = 0;  // the face whose side the tangents are on
  int slots(bool catmark) const { return 1 + edges + (catmark ? faces : 0); }
};

// Position, first and second tangent weights on the disk's slots; the tangents' cross product
// points along the side's face orientation. Empty tangents where the limit has no tangent plane
// the ring's matrix shows (a smooth vertex of valence 2: the caller keeps Far's).
struct RingMasks {
  std::vector<double> position, first, second;
};

// Whether Far's limit masks are the limit at a vertex of this ring and its rules repeat: the
// cases Sdc's masks may be applied as they are (an interior crease on the side its ring starts in).
bool far_masks_exact(const RingDisk& disk, SubdivisionRule rule);

// Throws std::invalid_argument for a ring Far refuses (a disk it cannot build).
RingMasks exact_ring_masks(const RingDisk& disk, SubdivisionRule rule, const OpenSubdiv::Sdc::Options& options);

}  // namespace sdb::refined
