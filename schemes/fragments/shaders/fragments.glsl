// What the fragment passes share: the bindings, the push constants, the scratch layout and the
// rule arithmetic. The arithmetic is kernel.cpp's, operation for operation (`precise`: no fused
// multiply-adds, no reassociation), so that a point shared by fragments comes out bit-identical
// in each, and the same as on the CPU.
//
// A work group is a chunk of a pass's entries for one batch (its work item): up to
// gl_WorkGroupSize.x fragments, one per invocation, of one shape (the tables the same for the whole
// group) or, for batches joined from shapes of few fragments, of several (each invocation reads its
// own shape's tables: a gather on lavapipe either way). Each invocation's slots sit in scratch with
// the lanes innermost, as the CPU kernel's Lanes<W>, one region per batch of the wave. A slot is
// one 16-byte element (x, y, z, 0): one texel fetch reads it and one vec4 store writes it.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x_id = 0) in;

layout(binding = 0) uniform usamplerBuffer tables;  // device_tables.h, r32ui texels
layout(binding = 10) uniform usamplerBuffer rule_texels;  // the same, rgba32ui: the rules (4-word aligned)
// Per batch: 0, first fragment, count, first slot of its scratch in the wave's.
layout(std430, binding = 1) readonly buffer Batches { uvec4 batch[]; };
layout(binding = 2) uniform usamplerBuffer fragment_words;  // control list, first vertex, shape
layout(binding = 3) uniform samplerBuffer control_floats;  // x y z per vertex
// Two halves: level d - 1's slots (from src_base) and level d's (from dst_base), this wave's.
layout(binding = 4) uniform samplerBuffer scratch_in;  // the scratch buffer, read (rgba32f)
layout(std430, binding = 7) restrict writeonly buffer ScratchOut { vec4 scratch_out[]; };  // and written (other slots)
layout(binding = 5, r32f) uniform restrict writeonly imageBuffer out_position;
layout(binding = 6, r32f) uniform restrict writeonly imageBuffer out_normal;
// The fragment's control points relative to its first (kernel.cpp's net tangents weigh these),
// laid out as a scratch half: the gather pass writes them, the limit's net normals read them.
layout(binding = 8) uniform samplerBuffer net_in;  // rgba32f
layout(std430, binding = 9) restrict writeonly buffer NetOut { vec4 net_out[]; };

// Every buffer is read through a texel view: on lavapipe a storage-buffer load is a loop over the
// lanes with a branch each, a texel fetch one gather (harness/gpu/README.md, "Memory access on
// lavapipe"). The scratch is written as storage buffers of vec4 (not 64-bit words: in time those
// cost more, harness/gpu/README.md), the output through r32f image views.
uint table_word(uint i) { return texelFetch(tables, int(i)).x; }
uvec4 rule_words(uint at) { return texelFetch(rule_texels, int(at / 4u)); }  // `at`: a multiple of 4
uint fragment_word(uint i) { return texelFetch(fragment_words, int(i)).x; }
float control_float(uint i) { return texelFetch(control_floats, int(i)).x; }
vec4 scratch_slot(uint i) { return texelFetch(scratch_in, int(i)); }

layout(push_constant) uniform Push {
  uint level;          // the level a level pass makes, 1 .. levels
  uint levels;
  uint first_batch;    // the wave's
  uint src_base;       // slots (16 bytes) into scratch: the half this pass reads
  uint dst_base;       // and the half it writes
  uint header_words;
  uint wave_first_vertex;
  uint out_shift;      // floats from the output bindings' start to the wave's first vertex
  uint chunk;          // entries of the pass per invocation (vulkan.cpp: llvmpipe's loop limit)
  uint kind_pairs;     // vertex points, limit: the word of this dispatch's kind's (list, count) pair for shape 0
  uint items;          // the word of this dispatch's first work item: (chunk, batch of the wave) per work group
  uint pad;            // (the rule's flags, the pass's part and the limit's kind are specialization constants)
  vec4 origin;         // the control box's centre: slots are relative to it
} pc;

const uint kCatmark = 1u, kProject = 2u;
// The pipeline's rule flags (kCatmark | kProject), part (kGather ...; pass_plan.h) and the kind
// of its entries (vertex points: a rule's kind; the limit: an entry's; device_tables.h):
// constants, so that a branch on them costs one side only (lavapipe runs both sides of a run-time
// branch).
layout(constant_id = 1) const uint kFlags = 0u;
layout(constant_id = 2) const uint kPart = 0u;
layout(constant_id = 3) const uint kKind = 0xfffu;
const uint kGather = 0u, kFaces = 1u, kEdges = 2u, kLimit = 3u, kVertices = 4u, kPatch = 5u;
const uint kHeaderPerLevel = 8u;
// Limit header fields (device_tables.h).
const uint kNumPositions = 0u, kPositions = 1u, kLimitRing = 2u, kStencil = 3u, kStencilBegin = 4u, kStencilSlot = 5u,
           kStencilW = 6u, kRegular = 7u, kRegularSize = 8u, kRegularSlots = 9u, kTangentBegin = 10u,
           kTangentSlot = 11u, kTangentW1 = 12u, kTangentW2 = 13u, kBlockVertices = 14u,
           kNumSlots0 = 15u, kNetSize = 16u, kNetTangents = 17u, kPatchSegments = 18u, kPatchWeights = 19u,
           kPatchParams = 20u, kNetSupportBegin = 21u, kNetSupport = 22u, kBlockSize = 23u, kNetStride = 24u;

uint g_lane, g_chunk, g_group, g_shape, g_fragment, g_count, g_scratch;

// False for invocations past the batch's fragments.
bool begin_invocation() {
  g_lane = gl_LocalInvocationID.x;
  g_chunk = table_word(pc.items + 2u * gl_WorkGroupID.x);
  g_group = table_word(pc.items + 2u * gl_WorkGroupID.x + 1u);
  const uvec4 b = batch[pc.first_batch + g_group];
  g_fragment = b.y + min(g_lane, b.z - 1u);
  g_shape = fragment_word(3u * g_fragment + 2u);
  g_count = b.z;
  g_scratch = b.w;
  return g_lane < b.z;
}

uint header() { return g_shape * pc.header_words; }

// This invocation's entries of a pass of `count`: [begin, end).
uvec2 chunk_of(uint count) {
  const uint begin = g_chunk * pc.chunk;
  return uvec2(min(begin, count), min(begin + pc.chunk, count));
}
uint limit_header() { return header() + kHeaderPerLevel * pc.levels; }

// Vertex points and limit: the dispatch's entries of the batch's shape, its kind's list (pass_plan.h).
uint kind_list() { return table_word(pc.kind_pairs + 2u * g_shape); }
uint kind_count() { return table_word(pc.kind_pairs + 2u * g_shape + 1u); }
float number(uint at) { return uintBitsToFloat(table_word(at)); }

// The batch's slots: each a row of its `count` lanes.
uint scratch_index(uint slot) { return g_scratch + slot * g_count + g_lane; }

vec3 load(bool from_dst, uint slot) { return scratch_slot((from_dst ? pc.dst_base : pc.src_base) + scratch_index(slot)).xyz; }
float load_axis(bool from_dst, uint slot, uint axis) {
  return scratch_slot((from_dst ? pc.dst_base : pc.src_base) + scratch_index(slot))[axis];
}
void store(uint slot, vec3 p) { scratch_out[pc.dst_base + scratch_index(slot)] = vec4(p, 0.0); }
vec3 load_net(uint slot) { return texelFetch(net_in, int(scratch_index(slot))).xyz; }
void store_net(uint slot, vec3 p) { net_out[scratch_index(slot)] = vec4(p, 0.0); }
vec3 control_point(uint v) { return vec3(control_float(3u * v), control_float(3u * v + 1u), control_float(3u * v + 2u)); }

// -0 as +0, by its bits (what kernel.cpp's "+ 0.0f" does, and no compiler can fold away): min and
// max cannot order two zeros.
float canonical(float x) { return floatBitsToUint(x) == 0x80000000u ? 0.0 : x; }

// kernel.cpp's sum3_symmetric: the largest of the three ways to add a, b and c.
precise float sum3_symmetric(float a, float b, float c) {
  precise float ab = (a + b) + c, bc = (b + c) + a, ca = (c + a) + b;
  return max(max(ab, bc), ca);
}

// The ring's terms in ascending order, summed from the smallest (kernel.cpp's sorting network and
// std::sort give this same sequence): each pass finds the next larger value and adds it as often
// as it occurs. No array, so any valence; O(n * distinct values).
precise float sorted_sum(bool from_dst, uint ref, uint n, uint axis) {
  precise float s = 0.0;
  float prev = 0.0;
  uint done = 0u;
  while (done < n) {
    float m = 0.0;
    bool found = false;
    for (uint i = 0u; i < n; ++i) {
      const float v = canonical(load_axis(from_dst, table_word(ref + i), axis));
      if ((done == 0u || v > prev) && (!found || v < m)) m = v, found = true;
    }
    uint count = 0u;
    for (uint i = 0u; i < n; ++i)
      if (canonical(load_axis(from_dst, table_word(ref + i), axis)) == m) ++count;
    if (!found || count == 0u) break;  // NaN: nothing orders it (inputs are checked; never loop forever)
    for (uint k = 0u; k < count; ++k) s = done + k == 0u ? m : s + m;
    done += count;
    prev = m;
  }
  return s;
}

// Ring cases (device_tables.h): a rule's ring of n terms is summed by the case's formula. A pass
// specialized on its entries' cases passes constants, and only that formula is compiled;
// kRingAny picks it from n at run time.
const uint kRingNone = 0u, kRingOne = 1u, kRingTwo = 2u, kRingFour = 3u, kRingSix = 4u, kRingEight = 5u,
           kRingSorted = 6u, kRingAny = 7u, kRuleAny = 127u;
uint ring_case_of(uint n) {
  return n == 0u ? kRingNone : n == 1u ? kRingOne : n == 2u ? kRingTwo : n == 4u ? kRingFour
       : n == 6u ? kRingSix : n == 8u ? kRingEight : kRingSorted;
}

// kernel.cpp's ring_sum: pairs for valence 4 and 8, pairs and a symmetric three for 6, sorted otherwise.
precise vec3 ring_sum(bool from_dst, uint ref, uint n, uint ring_case) {
  const uint c = ring_case == kRingAny ? ring_case_of(n) : ring_case;
  precise vec3 r;
  if (c == kRingOne) {
    r = load(from_dst, table_word(ref));
  } else if (c == kRingTwo) {
    r = load(from_dst, table_word(ref)) + load(from_dst, table_word(ref + 1u));
  } else if (c == kRingFour) {
    r = (load(from_dst, table_word(ref)) + load(from_dst, table_word(ref + 2u))) + (load(from_dst, table_word(ref + 1u)) + load(from_dst, table_word(ref + 3u)));
  } else if (c == kRingSix) {
    precise vec3 a = load(from_dst, table_word(ref)) + load(from_dst, table_word(ref + 3u));
    precise vec3 b = load(from_dst, table_word(ref + 1u)) + load(from_dst, table_word(ref + 4u));
    precise vec3 c = load(from_dst, table_word(ref + 2u)) + load(from_dst, table_word(ref + 5u));
    r = vec3(sum3_symmetric(a.x, b.x, c.x), sum3_symmetric(a.y, b.y, c.y), sum3_symmetric(a.z, b.z, c.z));
  } else if (c == kRingEight) {
    precise vec3 q0 = load(from_dst, table_word(ref)) + load(from_dst, table_word(ref + 4u));
    precise vec3 q1 = load(from_dst, table_word(ref + 1u)) + load(from_dst, table_word(ref + 5u));
    precise vec3 q2 = load(from_dst, table_word(ref + 2u)) + load(from_dst, table_word(ref + 6u));
    precise vec3 q3 = load(from_dst, table_word(ref + 3u)) + load(from_dst, table_word(ref + 7u));
    r = (q0 + q2) + (q1 + q3);
  } else {
    r = vec3(sorted_sum(from_dst, ref, n, 0u), sorted_sum(from_dst, ref, n, 1u), sorted_sum(from_dst, ref, n, 2u));
  }
  return r;
}

// kernel.cpp's apply(): wv c + wc (p0 + p1) + we sum(e) + wf sum(f). The centre, pair and ring are
// read from src; the f terms from dst when faces_in_dst (Catmull-Clark's new face points).
// `rule_case`: the e and f terms' ring cases and whether wc is used (device_tables.h), or
// kRuleAny to take them from the rule.
precise vec3 apply_vertex_rule(uint at, uint ring, bool faces_in_dst, uint rule_case) {
  const uvec4 r0 = rule_words(at), r1 = rule_words(at + 4u);
  const uint counts = r1.x;
  const uint num_e = counts & 0xffffu, num_f = counts >> 16;
  const float wv = uintBitsToFloat(r1.y), wc = uintBitsToFloat(r1.z), we = uintBitsToFloat(r1.w);
  const float wf = uintBitsToFloat(rule_words(at + 8u).x);
  const bool any = rule_case == kRuleAny;
  const uint e_case = any ? ring_case_of(num_e) : rule_case & 7u, f_case = any ? ring_case_of(num_f) : (rule_case >> 3) & 7u;
  const bool wc_term = any ? wc != 0.0 : (rule_case & 64u) != 0u;
  const uint ref = ring + r0.w;
  precise vec3 s = load(false, r0.x) * wv;
  if (wc_term) s = s + (load(false, r0.y) + load(false, r0.z)) * wc;
  if (e_case != kRingNone) s = s + ring_sum(false, ref, num_e, e_case) * we;
  if (f_case != kRingNone) s = s + ring_sum(faces_in_dst, ref + num_e, num_f, f_case) * wf;
  return s;
}
