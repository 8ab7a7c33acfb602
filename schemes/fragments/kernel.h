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

// One slot of W fragments, structure of arrays. W = kLanes for shapes many fragments share, 1
// for the rest (a vertex patch's shape is often its own).
template <int W>
struct Lanes {
  float x[W], y[W], z[W];
};

// parent: level d - 1's slots; child: level d's (table.num_slots). Catmull-Clark edge and vertex
// rules read the face points just written to `child`.
template <int W>
void refine_level(const LevelTable& table, bool catmark, const Lanes<W>* parent, Lanes<W>* child);

// Limit position of every position entry and unit normal of every tangent entry, from the last
// level's slots; with project = false the positions are the last level's points themselves (the
// exactness oracle's side), the normals still the limit's. `net`: the level-0 slots relative to
// the first (tables.h, net_tangents), read where the table has net tangents. `local_last`, where
// not null: the last level refined from `net` instead, for the tangents of every entry but those
// at control vertices (LimitTable::at_control_vertex).
template <int W>
void project_to_limit(const LimitTable& table, const Lanes<W>* last, const Lanes<W>* net, const Lanes<W>* local_last,
                      bool project, Lanes<W>* position, Lanes<W>* normal);

}  // namespace sdb::fragments
