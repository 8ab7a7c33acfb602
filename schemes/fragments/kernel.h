// The generic refinement kernel: applies a shape's pattern tables to kLanes fragments of that
// shape at once, one fragment per lane (the CPU's counterpart of a work group's invocations: the
// tables are shared, so every rule is the same arithmetic across the lanes and compiles to SIMD
// with no gathers). It knows no topology, only the rule forms of tables.h. Every lane does the
// same arithmetic in the same order as the Vulkan shader will (README.md), so points shared by
// fragments are bit-identical.
#pragma once

#include "schemes/fragments/tables.h"

namespace sdb::fragments {

constexpr int kLanes = 8;

// One slot of kLanes fragments, structure of arrays.
struct Lanes {
  float x[kLanes], y[kLanes], z[kLanes];
};

// parent: level d - 1's slots; child: level d's (table.num_slots). Catmull-Clark edge and vertex
// rules read the face points just written to `child`.
void refine_level(const LevelTable& table, bool catmark, const Lanes* parent, Lanes* child);

// Limit position of every position entry and unit normal of every tangent entry, from the last
// level's slots; with project = false the positions are the last level's points themselves (the
// exactness oracle's side), the normals still the limit's.
void project_to_limit(const LimitTable& table, const Lanes* last, bool project, Lanes* position, Lanes* normal);

}  // namespace sdb::fragments
