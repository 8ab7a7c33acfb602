#version 450
// The D-facet visit of a step (one class of target nodes: vertex points, the two kinds of edge
// points, facet or diagonal points; a pipeline per class), or the limit projection of the D-facets'
// interiors. One invocation per target node; all D-facets of the pass are of one kind. The table
// holds, per target of a D-facet, its source square (a << 16 | b) and its offset in the interior.
#include "mipgh.glsl"

layout(constant_id = 1) const bool kQuad = true;
layout(constant_id = 2) const uint kClass = 0u;  // 0..3, or 4: the limit
const uint kLimit = 4u;

uint g_base;
vec3 P(int i, int j) {
  const uint n = pc.n;
  const uint at = kQuad ? uint(i) * n + uint(j) : uint(i) * n - uint(i * (i - 1) / 2) + uint(j);
  return node(texelFetch(lod, int(g_base + at)).x);
}

void main() {
  const uint i = SDB_LINEAR_INVOCATION();
  if (i >= pc.count) return;
  const uint f = i / pc.per_item, k = i - f * pc.per_item;
  const bool listed = pc.facet_list != 0u;  // D-facets of both kinds: where each one's array and interior are
  const uint first = listed ? word(pc.facet_list + 2u * f + 1u) : pc.dst_base + f * pc.interior;
  const uint ab = word(pc.table + 2u * k), target = first + word(pc.table + 2u * k + 1u);
  const int a = int(ab >> 16u), b = int(ab & 0xffffu);
  g_base = pc.lod_base + (listed ? word(pc.facet_list + 2u * f) : f * pc.facet_nodes);
  precise vec3 p;
  if (kQuad) {
    if (kClass == 0u) {
      p = 0.5625 * P(a, b) + 0.09375 * ((P(a, b + 1) + P(a, b - 1)) + (P(a + 1, b) + P(a - 1, b))) +
          0.015625 * ((P(a + 1, b + 1) + P(a - 1, b - 1)) + (P(a + 1, b - 1) + P(a - 1, b + 1)));
    } else if (kClass == 1u) {
      p = 0.375 * (P(a, b) + P(a, b + 1)) + 0.0625 * ((P(a - 1, b) + P(a - 1, b + 1)) + (P(a + 1, b) + P(a + 1, b + 1)));
    } else if (kClass == 2u) {
      p = 0.375 * (P(a, b) + P(a + 1, b)) + 0.0625 * ((P(a, b - 1) + P(a + 1, b - 1)) + (P(a, b + 1) + P(a + 1, b + 1)));
    } else if (kClass == 3u) {
      p = 0.25 * ((P(a, b) + P(a + 1, b + 1)) + (P(a, b + 1) + P(a + 1, b)));
    } else {
      const vec3 c = P(a, b), e0 = P(a, b + 1), e1 = P(a + 1, b), e2 = P(a, b - 1), e3 = P(a - 1, b);
      const vec3 d0 = P(a + 1, b + 1), d1 = P(a + 1, b - 1), d2 = P(a - 1, b - 1), d3 = P(a - 1, b + 1);
      p = (1.0 / 36.0) * (16.0 * c + 4.0 * ((e0 + e2) + (e1 + e3)) + ((d0 + d2) + (d1 + d3)));
      precise vec3 t1 = 4.0 * (e0 - e2) + ((d0 + d3) - (d1 + d2));
      precise vec3 t2 = 4.0 * (e1 - e3) + ((d0 + d1) - (d2 + d3));
      store_normal(target, unit(t1, t2));
    }
  } else {
    if (kClass == 0u) {
      p = 0.625 * P(a, b) +
          0.0625 * (((P(a, b + 1) + P(a, b - 1)) + (P(a + 1, b) + P(a - 1, b))) + (P(a + 1, b - 1) + P(a - 1, b + 1)));
    } else if (kClass == 1u) {
      p = 0.375 * (P(a, b) + P(a, b + 1)) + 0.125 * (P(a + 1, b) + P(a - 1, b + 1));
    } else if (kClass == 2u) {
      p = 0.375 * (P(a, b) + P(a + 1, b)) + 0.125 * (P(a, b + 1) + P(a + 1, b - 1));
    } else if (kClass == 3u) {
      p = 0.375 * (P(a, b + 1) + P(a + 1, b)) + 0.125 * (P(a, b) + P(a + 1, b + 1));
    } else {
      const vec3 c = P(a, b), e0 = P(a, b + 1), e1 = P(a + 1, b), e2 = P(a + 1, b - 1), e3 = P(a, b - 1);
      const vec3 e4 = P(a - 1, b), e5 = P(a - 1, b + 1);
      p = 0.5 * c + (1.0 / 12.0) * (((e0 + e3) + (e1 + e4)) + (e2 + e5));
      precise vec3 t1 = (e0 - e3) + 0.5 * ((e1 - e2) - (e4 - e5));
      precise vec3 t2 = (e1 + e2) - (e4 + e5);
      store_normal(target, unit(t1, t2));
    }
  }
  store(target, p);
}
