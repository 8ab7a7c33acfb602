#version 450
// Limit projection of the last level and the output: for every vertex of the fragment's blocks,
// its limit position (symmetric, kernel.cpp's) and unit normal. A dispatch takes the entries of
// one kind (device_tables.h, limit_kind), the kind a specialization constant: lavapipe compiles
// the kind's paths alone instead of running every path masked.
#include "fragments.glsl"

const uint kRuleCase = kKind & 127u, kPositionCase = (kKind >> 7) & 3u, kNormalCase = (kKind >> 9) & 7u;
const uint kPositionRule = 0u, kPositionStencil = 1u, kPositionAny = 2u;
const uint kNormalNet = 0u, kNormalRegular9 = 1u, kNormalRegular7 = 2u, kNormalGeneral = 3u, kNormalAny = 4u,
           kNormalPatch = 5u;  // patch_normals.comp writes it

// Long tangent masks (a pole's ring) in compensated sums: the CPU sums them in double
// (kernel.cpp), float alone would lose the normal's precision at valence 360.
const uint kLongTangentMask = 32u;

precise vec3 limit_position(uint lh, uint entry) {
  const uint at = table_word(lh + kPositions) + 12u * entry;
  precise vec3 p;
  if ((kFlags & kProject) == 0u) {
    p = load(false, rule_words(at).x);
    return p;
  }
  const int stencil = kPositionCase == kPositionRule ? -1 : int(table_word(table_word(lh + kStencil) + entry));
  if (kPositionCase != kPositionStencil && stencil < 0) {
    p = apply_vertex_rule(at, table_word(lh + kLimitRing), false, kRuleCase);
    return p;
  }
  p = vec3(0.0);  // in the stencil's order, which every fragment shares
  const uint begin = table_word(table_word(lh + kStencilBegin) + uint(stencil)), end = table_word(table_word(lh + kStencilBegin) + uint(stencil) + 1u);
  for (uint k = begin; k < end; ++k) p = p + load(false, table_word(table_word(lh + kStencilSlot) + k)) * number(table_word(lh + kStencilW) + k);
  return p;
}

precise vec3 unit_normal(vec3 a, vec3 b) {
  precise vec3 c = vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
  precise float len2 = c.x * c.x + c.y * c.y + c.z * c.z;
  precise float k = len2 > 0.0 ? 1.0 / sqrt(len2) : 0.0;
  precise vec3 n = c * k;
  return n;
}

// kernel.cpp's regular_normal: Sdc's regular tangents as differences. Slots: centre, e, f.
precise vec3 regular_normal(uint slots, uint size) {
  if (size == 9u) {
    precise vec3 d02 = load(false, table_word(slots + 5u)) - load(false, table_word(slots + 7u));
    precise vec3 d13 = load(false, table_word(slots + 6u)) - load(false, table_word(slots + 8u));
    precise vec3 a = (load(false, table_word(slots + 1u)) - load(false, table_word(slots + 3u))) * 4.0 + (d02 - d13);
    precise vec3 b = (load(false, table_word(slots + 2u)) - load(false, table_word(slots + 4u))) * 4.0 + (d02 + d13);
    return unit_normal(a, b);
  }
  precise vec3 d14 = load(false, table_word(slots + 2u)) - load(false, table_word(slots + 5u));
  precise vec3 d25 = load(false, table_word(slots + 3u)) - load(false, table_word(slots + 6u));
  precise vec3 a = (load(false, table_word(slots + 1u)) - load(false, table_word(slots + 4u))) + (d14 - d25) * 0.5;
  precise vec3 b = (d14 + d25) * 0.866025404;
  return unit_normal(a, b);
}

precise vec3 general_normal(uint lh, uint entry) {
  const uint begin = table_word(table_word(lh + kTangentBegin) + entry), end = table_word(table_word(lh + kTangentBegin) + entry + 1u);
  const uint slot = table_word(lh + kTangentSlot), w1 = table_word(lh + kTangentW1), w2 = table_word(lh + kTangentW2);
  precise vec3 a = vec3(0.0), b = vec3(0.0), ca = vec3(0.0), cb = vec3(0.0);
  const bool compensated = end - begin > kLongTangentMask;
  for (uint k = begin; k < end; ++k) {
    const vec3 p = load(false, table_word(slot + k));
    precise vec3 ta = p * number(w1 + k), tb = p * number(w2 + k);
    if (!compensated) {
      a = a + ta, b = b + tb;
      continue;
    }
    // Neumaier's sum: the rounding error of each addition kept apart, added at the end.
    precise vec3 sa = a + ta, sb = b + tb;
    ca = ca + mix((ta - sa) + a, (a - sa) + ta, greaterThanEqual(abs(a), abs(ta)));
    cb = cb + mix((tb - sb) + b, (b - sb) + tb, greaterThanEqual(abs(b), abs(tb)));
    a = sa, b = sb;
  }
  return unit_normal(a + ca, b + cb);
}

// kernel.cpp's net_normal: the tangents as weights on the control points relative to the first
// (the gather pass's net points), over the block's support alone (the control points its weights
// do not leave at 0), in the same order: the multi-fragment CPU kernel's sums. Two control points
// a step, their weights one uvec4 (device_tables.cpp, net_pairs; an odd support's last pair adds
// the origin, 0).
precise vec3 net_normal(uint lh, uint entry) {
  const uint w = table_word(lh + kNetTangents) + table_word(lh + kNetStride) * entry;
  const uint block = entry / table_word(lh + kBlockSize), begins = table_word(lh + kNetSupportBegin);
  const uint support = table_word(lh + kNetSupport), begin = table_word(begins + block);
  const uint end = table_word(begins + block + 1u);
  precise vec3 a = vec3(0.0), b = vec3(0.0);
  for (uint k = begin; k < end; k += 2u) {
    const vec4 weights = uintBitsToFloat(rule_words(w + 2u * (k - begin)));
    const vec3 p = load_net(table_word(support + k)), q = load_net(table_word(support + k + 1u));
    a = a + p * weights.x, b = b + p * weights.y;
    a = a + q * weights.z, b = b + q * weights.w;
  }
  return unit_normal(a, b);
}

precise vec3 limit_normal(uint lh, uint entry) {
  if (kNormalCase == kNormalNet || (kNormalCase == kNormalAny && table_word(lh + kNetSize) != 0u)) return net_normal(lh, entry);
  if (kNormalCase == kNormalGeneral) return general_normal(lh, entry);
  const int regular = int(table_word(table_word(lh + kRegular) + entry));
  if (kNormalCase != kNormalAny || regular >= 0) {
    const uint size = kNormalCase == kNormalRegular9 ? 9u : kNormalCase == kNormalRegular7 ? 7u : table_word(lh + kRegularSize);
    return regular_normal(table_word(lh + kRegularSlots) + uint(regular) * size, size);
  }
  return general_normal(lh, entry);
}

void main() {
  if (!begin_invocation()) return;
  const uint lh = limit_header();
  const uint first = 3u * (fragment_word(3u * g_fragment + 1u) - pc.wave_first_vertex) + pc.out_shift;
  const uint list = kind_list();
  const uvec2 range = chunk_of(kind_count());
  for (uint j = range.x; j < range.y; ++j) {
    const uint i = table_word(list + j);
    precise vec3 p = limit_position(lh, i) + pc.origin.xyz;
    const uint o = first + 3u * i;
    if (kNormalCase != kNormalPatch && (kNormalCase != kNormalAny || table_word(lh + kPatchSegments) == 0u)) {
      const vec3 nrm = limit_normal(lh, i);
      imageStore(out_normal, int(o), vec4(nrm.x));
      imageStore(out_normal, int(o + 1u), vec4(nrm.y));
      imageStore(out_normal, int(o + 2u), vec4(nrm.z));
    }
    imageStore(out_position, int(o), vec4(p.x));
    imageStore(out_position, int(o + 1u), vec4(p.y));
    imageStore(out_position, int(o + 2u), vec4(p.z));
  }
}
