// The generic refinement kernel: applies a shape's pattern tables to one fragment's slots. It
// knows no topology, only the three rule forms of tables.h. The same arithmetic, in the same
// order, is what the Vulkan shader does (README.md), so that shared points are bit-identical.
#pragma once

#include "harness/core/control_mesh.h"
#include "schemes/fragments/tables.h"

namespace sdb::fragments {

struct Vec3 {
  float x, y, z;
};

// parent: level d - 1's slots; child: level d's (table.num_slots). Catmull-Clark edge and vertex
// rules read the face points just written to `child`.
void refine_level(const LevelTable& table, bool catmark, const Vec3* parent, Vec3* child);

// Limit position and unit normal of every limit entry, from the last level's slots.
void project_to_limit(const LimitTable& table, const Vec3* last, Vec3* position, Vec3* normal);

// The last level's points themselves (no projection), for the exactness test; normals as above.
void refined_points(const LimitTable& table, const Vec3* last, Vec3* position, Vec3* normal);

}  // namespace sdb::fragments
