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

// One slot of W fragments, structure of arrays.
template <int W>
struct Lanes {
  float x[W], y[W], z[W];
};

// One slot of a fragment whose shape is its own (a vertex patch's often is): its point twice,
// relative to the control box's centre (what the output takes) and relative to its first control
// point (what its tangents take, tables.h at_control_vertex), each padded with a zero. Both
// refinements are then one 8-float vector operation per rule term, the same arithmetic per float
// as kLanes lanes get, so the same bits.
struct Pair {
  float centred[4], local[4];
};

// A Pair in a slot as wide as Lanes<kLanes>: both kernels' level buffers step kSlotBytes a slot,
// so one set of tables, its slots named by byte offset, serves both (address_in_bytes).
struct PairSlot {
  Pair pair;
  float unused[16];
};
constexpr uint32_t kSlotBytes = sizeof(Lanes<kLanes>);
static_assert(sizeof(PairSlot) == kSlotBytes);

// Every slot a table names (rules, rings, stencils, tangent slots) as its byte offset in a level
// buffer, slot x kSlotBytes: the kernel's loads then take a table entry as their displacement,
// where computing slot x 96 took two instructions a load (a tenth of the kernel's). In prepare,
// once; the CPU kernel reads its tables only this way. Throws Unsupported past 2^32 bytes.
void address_in_bytes(ShapeTables& t);

// parent: level d - 1's slots; child: level d's (table.num_slots). Catmull-Clark edge and vertex
// rules read the face points just written to `child`. Slot: Lanes<kLanes> or PairSlot.
template <class Slot>
void refine_level(const LevelTable& table, bool catmark, const Slot* parent, Slot* child);

// Limit position of every position entry and unit normal of every tangent entry, from the last
// level's slots; with project = false the positions are the last level's points themselves (the
// exactness oracle's side), the normals still the limit's. `net`: the level-0 slots relative to
// the first (tables.h, net_tangents), read where the table has net tangents.
void project_to_limit(const LimitTable& table, const Lanes<kLanes>* last, const Lanes<kLanes>* net, bool project,
                      Lanes<kLanes>* position, Lanes<kLanes>* normal);

// Copies the first `count` limit entries of the kLanes lanes (their output blocks' vertices in
// order, tables.h) into their outputs pos[l], nrm[l], adding `origin` to the positions. Every lane
// writes, the copy unrolled over all eight: lanes past a batch point at its last fragment's
// output, which they computed again (run_lanes), so they write the same bits there.
void write_blocks(const Lanes<kLanes>* position, const Lanes<kLanes>* normal, uint32_t count, const float* origin,
                  float* const* pos, float* const* nrm);

// The same for one fragment refined as Pairs: positions from the centred halves; tangents from
// the local halves (net tangents, read from `net`, only at control vertices: streaming 2 x
// net_size weights for every vertex made the bunny 33% slower), from the centred ones where the
// shape has no net tangents. `level0`: the first level's slots (the patch polynomial's net).
void project_to_limit(const LimitTable& table, const PairSlot* last, const PairSlot* level0, const Lanes<1>* net,
                      bool project, Pair* position, Lanes<1>* normal);

}  // namespace sdb::fragments
