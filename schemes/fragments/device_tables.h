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
// Rules: a face 4 words (a b c d), an edge 8 (v0 v1 f0 f1 wv wf, 2 unused), a vertex 12
// (centre p0 p1 ring num_e|num_f<<16 wv wc we wf, 3 unused), each list from a multiple of 4 words:
// the shaders read a rule as 1, 2 or 3 uvec4 texels instead of 4, 6 or 9 words (on lavapipe a
// texel fetch costs about the same whatever its width). Offsets are word indices into `words`.
constexpr uint32_t kHeaderPerLevel = 8;
// Limit header (at kHeaderPerLevel * levels): num_positions, positions, ring, stencil, stencil_begin,
// stencil_slot, stencil_w, regular, regular_size, regular_slots, tangent_begin, tangent_slot,
// tangent_w1, tangent_w2, block_vertices, num_slots0, net_size, net_tangents, patch_segments (0:
// no patch polynomial), patch_weights, patch_params (the s + 1 floats i / s), net_support_begin,
// net_support, block_size (the vertices of one block), net_stride. The net tangents, support and
// stride are device_tables.cpp's net_pairs layout. The limit's entries are the output blocks'
// vertices in order (tables.h).
constexpr uint32_t kHeaderLimit = 25;
enum LimitField : uint32_t {
  kNumPositions, kPositions, kLimitRing, kStencil, kStencilBegin, kStencilSlot, kStencilW,
  kRegular, kRegularSize, kRegularSlots, kTangentBegin, kTangentSlot, kTangentW1, kTangentW2,
  kBlockVertices, kNumSlots0, kNetSize, kNetTangents, kPatchSegments, kPatchWeights, kPatchParams,
  kNetSupportBegin, kNetSupport, kBlockSize, kNetStride,
};

struct DeviceTables {
  uint32_t levels = 0;  // refinement levels (the surface's inner depth), the same for every shape
  uint32_t header_words = 0;
  std::vector<uint32_t> words;
  // Three words per fragment, in the surface's `order`: its control list (into `words`), its
  // first output vertex and its shape.
  std::vector<uint32_t> fragments;
};

// Throws Unsupported past 2^32 words or output vertices.
DeviceTables pack_tables(const FragmentSurface& surface);

// Kinds of entries (pass_plan.h): a vertex rule's by the formulas its terms take (fragments.glsl's
// apply_vertex_rule), a limit entry's also by the paths of its position and normal (limit.comp).
// A kind is a specialization constant of the pass's pipeline, so that lavapipe, which runs both
// sides of every branch masked, compiles one path; kRuleAny and kLimitAny decide at run time.
// A rule's kind: bits 0-2 and 3-5 the ring cases of its e and f terms, bit 6 a wc term. A limit
// entry's: bits 0-6 its position's rule, bits 7-8 the position's path, bits 9-11 the normal's
// (kNormalPatch: none here, the patch pass writes it).
enum RingCase : uint32_t { kRingNone, kRingOne, kRingTwo, kRingFour, kRingSix, kRingEight, kRingSorted, kRingAny };
constexpr uint32_t kRuleAny = 127;
enum PositionCase : uint32_t { kPositionRule, kPositionStencil, kPositionAny };
enum NormalCase : uint32_t { kNormalNet, kNormalRegular9, kNormalRegular7, kNormalGeneral, kNormalAny, kNormalPatch };
constexpr uint32_t kind_of(uint32_t rule, PositionCase position, NormalCase normal) {
  return rule | uint32_t(position) << 7 | uint32_t(normal) << 9;
}
constexpr uint32_t kLimitAny = kind_of(kRuleAny, kPositionAny, kNormalAny);
uint32_t rule_kind(const VertexRule& r);
// Entry `entry` of shape `t`'s limit; `project`: the positions are projected to the limit.
uint32_t limit_kind(const ShapeTables& t, uint32_t entry, bool project);

// Entry lists of a pass's dispatches: lists[k][shape] are the entries of kind k, ascending.
// Appends, kind-major, a (first word, count) pair per kind and shape, then the lists; returns the
// word of the first pair (kind k's pair for a shape is at that + 2 (k shapes + shape)).
uint32_t append_kind_lists(DeviceTables& d, const std::vector<std::vector<std::vector<uint32_t>>>& lists);

}  // namespace sdb::fragments
