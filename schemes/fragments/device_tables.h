// The pattern tables of every shape, flattened into one array of 32-bit words for the Vulkan
// kernel (shaders/fragments.glsl reads this layout; keep the two in step). The same tables the
// CPU kernel applies, rule for rule and term for term, so both sides do the same arithmetic.
//
// words: per shape a header of header_words (kHeaderPerLevel per level, then the limit's
// kHeaderLimit), then the rules, then each fragment's control-vertex list (level-0 slots).
// Floats are stored as their bits.
#pragma once

#include <cstdint>
#include <vector>

#include "schemes/fragments/surface.h"

namespace sdb::fragments {

// Level header: num_slots, num_faces, faces, num_edges, edges, num_vertices, vertices, ring.
// Rules: a face 4 words (a b c d), an edge 6 (v0 v1 f0 f1 wv wf), a vertex 9
// (centre p0 p1 ring num_e|num_f<<16 wv wc we wf); offsets are word indices into `words`.
constexpr uint32_t kHeaderPerLevel = 8;
// Limit header (at kHeaderPerLevel * levels): num_positions, positions, ring, stencil, stencil_begin,
// stencil_slot, stencil_w, regular, regular_size, regular_slots, tangent_begin, tangent_slot,
// tangent_w1, tangent_w2, block_vertices, num_slots0, net_size, net_tangents. The limit's entries
// are the output blocks' vertices in order (tables.h).
constexpr uint32_t kHeaderLimit = 18;
enum LimitField : uint32_t {
  kNumPositions, kPositions, kLimitRing, kStencil, kStencilBegin, kStencilSlot, kStencilW,
  kRegular, kRegularSize, kRegularSlots, kTangentBegin, kTangentSlot, kTangentW1, kTangentW2,
  kBlockVertices, kNumSlots0, kNetSize, kNetTangents,
};

struct DeviceTables {
  uint32_t levels = 0;  // refinement levels (the surface's inner depth), the same for every shape
  uint32_t header_words = 0;
  std::vector<uint32_t> words;
  // Two words per fragment, in the surface's `order`: its control list (into `words`) and its
  // first output vertex.
  std::vector<uint32_t> fragments;
};

// Throws Unsupported past 2^32 words or output vertices.
DeviceTables pack_tables(const FragmentSurface& surface);

}  // namespace sdb::fragments
