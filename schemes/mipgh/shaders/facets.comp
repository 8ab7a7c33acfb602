#version 450
// The D-facet visit of a step, or the limit projection of the D-facets' interiors; all D-facets of
// one pass are of one kind. One invocation per block of targets of a D-facet's interior
// (vulkan.cpp, facet_blocks), whose stencils lie in one window of nodes, fetched once (a D-LoD
// index and a node each):
// - a step: nodes (a, b) and (a, b + 1) at level sigma and the targets each owns at sigma + 1,
//   the vertex point (2a, 2b), the edge points (2a, 2b + 1) and (2a + 1, 2b), the facet or
//   diagonal point (2a + 1, 2b + 1): the 3 x 4 nodes around them, where an invocation per target
//   fetched 4 to 9 nodes for one and one per node 9 for four;
// - the limit: nodes (a, b) .. (a + 1, b + 3): the 4 x 6 nodes around them, where an invocation
//   per node fetched 9 (quads) or 7 (triangles) and one per 2 x 2 nodes 16.
// And one dispatch per kind, not one per class of target. The table holds per block (a << 16 | b);
// its targets' offsets in the interior are worked out here (interior_offset; kNoTarget where a
// target is outside it).
//
// Each target's sum is the CPU's (tile.cpp), in its order.
#extension GL_EXT_control_flow_attributes : require
#include "mipgh.glsl"

layout(constant_id = 1) const bool kQuad = true;
layout(constant_id = 2) const uint kClass = 0u;  // 0: a step, 1: the limit
const uint kLimit = 1u;
const uint kNoTarget = 0xffffffffu;  // vulkan.cpp's kNoTarget
const int kStepNodes = 2, kLimitColumns = 4;  // vulkan.cpp's: a block's nodes (a step) or columns (the limit)
const uint kTargets = kClass == kLimit ? uint(2 * kLimitColumns) : uint(4 * kStepNodes);

uint g_base;
// vulkan.cpp's interior_offset: node (r, c), 1-based, of an interior `width` nodes wide (triangles:
// row r is width - r long), or kNoTarget outside it.
uint interior_offset(int width, int r, int c) {
  const int row_width = kQuad ? width : width - r;
  if (r < 1 || r > width || c < 1 || c > row_width) return kNoTarget;
  const int before = kQuad ? (r - 1) * width : (r - 1) * width - ((r - 1) * r) / 2;
  return uint(before + c - 1);
}

// Node (i, j) of the D-facet at level sigma; (i, j) clamped into the D-facet's array, for the
// window's nodes past its edge that only targets outside the interior would read.
vec3 P(int i, int j) {
  const int last = int(pc.n) - 1;
  i = clamp(i, 0, last);
  j = clamp(j, 0, kQuad ? last : last - i);
  const uint n = pc.n;
  const uint at = kQuad ? uint(i) * n + uint(j) : uint(i) * n - uint(i * (i - 1) / 2) + uint(j);
  return node(texelFetch(lod, int(g_base + at)).x);
}

// The window around the block's node (a, b): W(da, db) is node (a + da, b + db), da in -1..1
// and db in -1..kStepNodes (a step), or da in -1..2 and db in -1..kLimitColumns (the limit).
vec3 g_window[4][kLimitColumns + 2];
vec3 g_node_window(int da, int db) { return g_window[da + 1][db + 1]; }

// A step's four targets of the block's node (a, b + m) in the order of its table: vertex point,
// edge point towards b + 1, edge point towards a + 1, facet (quads) or diagonal (triangles) point.
vec3 step_target(uint c, int m) {
#define W(da, db) g_node_window(da, (db) + m)
  precise vec3 p;
  if (kQuad) {
    if (c == 0u) {
      p = 0.5625 * W(0, 0) + 0.09375 * ((W(0, 1) + W(0, -1)) + (W(1, 0) + W(-1, 0))) +
          0.015625 * ((W(1, 1) + W(-1, -1)) + (W(1, -1) + W(-1, 1)));
    } else if (c == 1u) {
      p = 0.375 * (W(0, 0) + W(0, 1)) + 0.0625 * ((W(-1, 0) + W(-1, 1)) + (W(1, 0) + W(1, 1)));
    } else if (c == 2u) {
      p = 0.375 * (W(0, 0) + W(1, 0)) + 0.0625 * ((W(0, -1) + W(1, -1)) + (W(0, 1) + W(1, 1)));
    } else {
      p = 0.25 * ((W(0, 0) + W(1, 1)) + (W(0, 1) + W(1, 0)));
    }
  } else {
    if (c == 0u) {
      p = 0.625 * W(0, 0) +
          0.0625 * (((W(0, 1) + W(0, -1)) + (W(1, 0) + W(-1, 0))) + (W(1, -1) + W(-1, 1)));
    } else if (c == 1u) {
      p = 0.375 * (W(0, 0) + W(0, 1)) + 0.125 * (W(1, 0) + W(-1, 1));
    } else if (c == 2u) {
      p = 0.375 * (W(0, 0) + W(1, 0)) + 0.125 * (W(0, 1) + W(1, -1));
    } else {
      p = 0.375 * (W(0, 1) + W(1, 0)) + 0.125 * (W(0, 0) + W(1, 1));
    }
  }
  return p;
#undef W
}
#define W(da, db) g_node_window(da, db)

// The limit at node (a + da, b + db) of the block, da, db in 0..1, into `target`.
void limit_target(int da, int db, uint target) {
  precise vec3 p;
  if (kQuad) {
    const vec3 c = W(da, db), e0 = W(da, db + 1), e1 = W(da + 1, db), e2 = W(da, db - 1), e3 = W(da - 1, db);
    const vec3 d0 = W(da + 1, db + 1), d1 = W(da + 1, db - 1), d2 = W(da - 1, db - 1), d3 = W(da - 1, db + 1);
    p = (1.0 / 36.0) * (16.0 * c + 4.0 * ((e0 + e2) + (e1 + e3)) + ((d0 + d2) + (d1 + d3)));
    precise vec3 t1 = 4.0 * (e0 - e2) + ((d0 + d3) - (d1 + d2));
    precise vec3 t2 = 4.0 * (e1 - e3) + ((d0 + d1) - (d2 + d3));
    store_normal(target, unit(t1, t2));
  } else {
    const vec3 c = W(da, db), e0 = W(da, db + 1), e1 = W(da + 1, db), e2 = W(da + 1, db - 1), e3 = W(da, db - 1);
    const vec3 e4 = W(da - 1, db), e5 = W(da - 1, db + 1);
    p = 0.5 * c + (1.0 / 12.0) * (((e0 + e3) + (e1 + e4)) + (e2 + e5));
    precise vec3 t1 = (e0 - e3) + 0.5 * ((e1 - e2) - (e4 - e5));
    precise vec3 t2 = (e1 + e2) - (e4 + e5);
    store_normal(target, unit(t1, t2));
  }
  store(target, p);
}

void main() {
  const uint i = SDB_LINEAR_INVOCATION();
  if (i >= pc.count) return;
  const uint f = i / pc.per_item, k = i - f * pc.per_item;
  const bool listed = pc.facet_list != 0u;  // D-facets of both kinds: where each one's array and interior are
  const uint first = listed ? word(pc.facet_list + 2u * f + 1u) : pc.dst_base + f * pc.interior;
  g_base = pc.lod_base + (listed ? word(pc.facet_list + 2u * f) : f * pc.facet_nodes);
  const uint ab = word(pc.table + k);
  const int a = int(ab >> 16u), b = int(ab & 0xffffu);
  const int rows = kClass == kLimit ? 2 : 1, columns = kClass == kLimit ? kLimitColumns : kStepNodes;
  [[unroll]] for (int da = -1; da <= rows; ++da)
    [[unroll]] for (int db = -1; db <= columns; ++db) g_window[da + 1][db + 1] = P(a + da, b + db);
  // The interior at the targets' level: level sigma's less its border (the limit), or sigma + 1's.
  const int width = kClass == kLimit ? int(pc.n) - 2 : 2 * int(pc.n) - 3;
  [[unroll]] for (uint c = 0u; c < kTargets; ++c) {
    if (kClass == kLimit) {
      const int i = int(c) / kLimitColumns, j = int(c) % kLimitColumns;
      const uint offset = interior_offset(width, a + i, b + j);
      if (offset != kNoTarget) limit_target(i, j, first + offset);
    } else {
      const int m = int(c >> 2u), i = int(c & 3u) >> 1, j = int(c & 1u);
      const uint offset = interior_offset(width, 2 * a + i, 2 * (b + m) + j);
      const vec3 p = step_target(c & 3u, m);
      if (offset != kNoTarget) store(first + offset, p);
    }
  }
}
