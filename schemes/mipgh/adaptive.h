// The criteria that label D-LoDs for adaptive refinement (Section 3.3, Figure 13: "labeled with
// the number of refinements ... explicitly at the outset by an application program"): a region,
// curvature, or the distance to a camera point. A label is the level a D-facet is refined to and
// drawn at; the DLoD (lod.h) lays out what the labels need, primitive compilation
// (primitives.h, compile_adaptive) closes the level changes.
#pragma once

#include <cstdint>
#include <vector>

#include "harness/core/control_mesh.h"
#include "schemes/mipgh/atlas.h"

namespace sdb::mipgh {

enum class Refinement {
  Uniform = 0,
  // Every D-facet whose centroid lies in the slab x <= lo.x + extent (hi.x - lo.x) of the
  // control box at the depth, the others at 0: the sharpest level change there is.
  Region = 1,
  // By the largest angle between a D-facet's normal and its neighbours' (its control net's
  // bend): the depth from extent times the mesh's largest angle up, proportionally less below.
  Curvature = 2,
  // By distance to a camera outside the box's largest corner (a quarter diagonal beyond it): the
  // nearest D-facet at the depth, one level less each time the distance grows by 2^extent.
  Camera = 3,
};

struct AdaptiveCriterion {
  Refinement kind = Refinement::Uniform;
  double extent = 0.5;  // in (0, 1]
};

// One label per D-facet, 0 .. depth.
std::vector<uint8_t> facet_labels(const DAtlas& atlas, const std::vector<Point3>& positions, AdaptiveCriterion c,
                                  int depth);

}  // namespace sdb::mipgh
