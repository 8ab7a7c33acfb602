// Fragment construction (prepare, untimed): the control mesh re-represented as overlapping local
// control nets. A vertex patch owns the faces around one extraordinary vertex, so that the
// irregularity lies strictly inside it; a facet patch owns one face. Each fragment's net is its
// owned faces plus every face touching one of their vertices (the 1-ring), which is what one
// refinement step needs to reproduce the owned faces' children and their 1-ring (README.md).
// Fragments whose nets are the same up to relabelling share one shape, and so one set of pattern
// tables (tables.h).
#pragma once

#include <vector>

#include "harness/core/control_mesh.h"

namespace sdb::fragments {

// A fragment's net in local labels, as a ControlMesh that OpenSubdiv can refine: owned faces
// first (with the global mesh's rotation, which fixes the ptex orientation of the output), then
// the 1-ring faces, each rotated to start at the owned vertex it was found from. Vertex labels
// follow first appearance, so the net, and its key, do not depend on global indices.
struct LocalNet {
  ControlMesh mesh;  // positions unused (zero); creases, corners, holes and rules as the input's
  int num_owned = 0;
};

struct Fragment {
  std::vector<int> owned_faces;  // global face indices; the output has one block per owned face
  std::vector<int> owned_starts;  // per owned face, the corner at its block's (0, 0) (describe())
  std::vector<int> control;      // global control vertex of each local vertex (level-0 slot)
  int shape = 0;                 // index into Partition::shapes
};

struct Partition {
  std::vector<Fragment> fragments;
  std::vector<LocalNet> shapes;  // distinct nets, in order of first use
  int vertex_patches = 0;
  int facet_patches = 0;
};

// `mesh` has passed the scheme's acceptance: manifold, all quads (Catmull-Clark) or all
// triangles (Loop). Faces tagged as holes own no fragment (but stay in their neighbours' nets).
Partition partition_mesh(const ControlMesh& mesh, SubdivisionRule rule);

}  // namespace sdb::fragments
