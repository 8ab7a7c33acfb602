#version 450
// The D-edge visit of a step or the limit projection of its nodes, for the fast D-edges (untagged,
// two D-facets of one kind), reading the strip's nodes through the side rows (processor.cpp's
// Strip: a on the edge, b one in from the major side, c one in from the minor side). The table
// holds per fast D-edge: its first node at the target level, the major D-facet and its side kind,
// the minor's.
//
// One invocation per kPairs pairs of targets along the edge, whose stencils share the strip's
// nodes:
// - a step: edge point t and vertex point t + 1 (t = 0 .. n - 2; the last edge point has none),
//   two pairs from the strip's nodes t .. t + 3: 12 node gathers where a pair apart took 9 and
//   a target apart 4 to 9;
// - the limit: nodes t .. t + 3 (t = 1, 5, ..; the last may be short), from t - 1 .. t + 4: 18
//   where two pairs apart took 24 and four nodes apart 36.
// Each target's sum is the CPU's, in its order.
#extension GL_EXT_control_flow_attributes : require
#include "mipgh.glsl"

layout(constant_id = 1) const bool kQuad = true;
layout(constant_id = 2) const uint kPart = 0u;
const uint kStep = 0u, kLimit = 1u;

uint g_major, g_minor, g_on, g_in, g_across, g_last;
// side_rows(sigma, size, side, depth) as processor.cpp lays them out: (kind * 2 + depth) * n.
uint row(uint kind, uint depth) { return pc.rows + (kind * 2u + depth) * pc.n; }
// The strip's nodes t, clamped into the strip: past its end only targets that do not exist read.
vec3 A(int t) { return node(texelFetch(lod, int(g_major + word(g_on + uint(clamp(t, 0, int(pc.n) - 1))))).x); }
vec3 B(int t) { return node(texelFetch(lod, int(g_major + word(g_in + uint(clamp(t, 0, int(g_last)))))).x); }
vec3 C(int t) { return node(texelFetch(lod, int(g_minor + word(g_across + g_last - uint(clamp(t, 0, int(g_last)))))).x); }

// Pairs of targets per invocation (vulkan.cpp's kEdgePairs): a step's edge points t0 .. t0 +
// kPairs - 1 with the vertex point after each, or the limit's nodes t0 .. t0 + 2 kPairs - 1.
const int kPairs = 2;
// The strip's nodes t0 - 1 .. t0 + 2 kPairs, fetched once: a_(d) is A(t0 + d), and so on (d is a
// constant wherever it is used: no array is indexed at run time).
vec3 g_a[2 * kPairs + 2], g_b[2 * kPairs + 2], g_c[2 * kPairs + 2];
vec3 a_(int d) { return g_a[d + 1]; }
vec3 b_(int d) { return g_b[d + 1]; }
vec3 c_(int d) { return g_c[d + 1]; }

// The targets at node t0 + t (t a constant).
vec3 edge_point(int t) {
  precise vec3 p;
  if (kQuad) p = 0.375 * (a_(t) + a_(t + 1)) + 0.0625 * ((b_(t) + b_(t + 1)) + (c_(t) + c_(t + 1)));
  else p = 0.375 * (a_(t) + a_(t + 1)) + 0.125 * (b_(t) + c_(t));
  return p;
}

vec3 vertex_point(int t) {
  precise vec3 p;
  if (kQuad) {
    p = 0.5625 * a_(t) + 0.09375 * ((a_(t + 1) + a_(t - 1)) + (b_(t) + c_(t))) +
        0.015625 * ((b_(t + 1) + c_(t - 1)) + (b_(t - 1) + c_(t + 1)));
  } else {
    p = 0.625 * a_(t) + 0.0625 * (((a_(t + 1) + a_(t - 1)) + (b_(t) + c_(t - 1))) + (b_(t - 1) + c_(t)));
  }
  return p;
}

// The limit at node t, the ring counter-clockwise seen from the major D-facet (processor.cpp,
// project_edge), into `target`.
void limit_node(int t, uint target) {
  precise vec3 p, t1, t2;
  if (kQuad) {
    const vec3 c = a_(t), e0 = a_(t + 1), e1 = b_(t), e2 = a_(t - 1), e3 = c_(t);
    const vec3 d0 = b_(t + 1), d1 = b_(t - 1), d2 = c_(t - 1), d3 = c_(t + 1);
    p = (1.0 / 36.0) * (16.0 * c + 4.0 * ((e0 + e2) + (e1 + e3)) + ((d0 + d2) + (d1 + d3)));
    t1 = 4.0 * (e0 - e2) + ((d0 + d3) - (d1 + d2));
    t2 = 4.0 * (e1 - e3) + ((d0 + d1) - (d2 + d3));
  } else {
    const vec3 c = a_(t), e0 = a_(t + 1), e1 = b_(t), e2 = b_(t - 1), e3 = a_(t - 1), e4 = c_(t - 1), e5 = c_(t);
    p = 0.5 * c + (1.0 / 12.0) * (((e0 + e3) + (e1 + e4)) + (e2 + e5));
    t1 = (e0 - e3) + 0.5 * ((e1 - e2) - (e4 - e5));
    t2 = (e1 + e2) - (e4 + e5);
  }
  store(target, p);
  store_normal(target, unit(t1, t2));
}

void main() {
  const uint i = SDB_LINEAR_INVOCATION();
  if (i >= pc.count) return;
  const uint q = i / pc.per_item, k = i - q * pc.per_item;
  const uint at = pc.table + 5u * q;
  const bool listed = pc.facet_lod != 0u;  // D-facets of both kinds: arrays of two sizes
  g_major = pc.lod_base + (listed ? word(pc.facet_lod + word(at + 1u)) : word(at + 1u) * pc.facet_nodes);
  g_minor = pc.lod_base + (listed ? word(pc.facet_lod + word(at + 3u)) : word(at + 3u) * pc.facet_nodes);
  g_on = row(word(at + 2u), 0u), g_in = row(word(at + 2u), 1u), g_across = row(word(at + 4u), 1u);
  g_last = kQuad ? pc.n - 1u : pc.n - 2u;
  const uint edge = word(at);  // the D-edge's first node at the target level
  // A step's pairs: edge point t, vertex point t + 1 (reads t .. t + 2), t = t0 .. t0 + kPairs - 1;
  // the limit's nodes t0 .. t0 + 2 kPairs - 1 (reads t0 - 1 .. t0 + 2 kPairs). Edge points are
  // 0 .. n - 2, vertex points and limit nodes 1 .. n - 2: the ones past them are not stored.
  const int t0 = kPart == kStep ? kPairs * int(k) : 1 + 2 * kPairs * int(k);
  const int lowest = kPart == kStep ? 0 : -1, highest = kPart == kStep ? kPairs + 1 : 2 * kPairs;
  [[unroll]] for (int d = lowest; d <= highest; ++d) {
    g_a[d + 1] = A(t0 + d), g_b[d + 1] = B(t0 + d), g_c[d + 1] = C(t0 + d);
  }
  const int last = int(pc.n) - 2;
  if (kPart == kStep) {
    [[unroll]] for (int m = 0; m < kPairs; ++m) {
      const vec3 e = edge_point(m), v = vertex_point(m + 1);
      const uint o = edge + 2u * uint(t0 + m);
      if (t0 + m <= last) store(o, e);
      if (t0 + m + 1 <= last) store(o + 1u, v);
    }
    return;
  }
  [[unroll]] for (int j = 0; j < 2 * kPairs; ++j)
    if (t0 + j <= last) limit_node(j, edge + uint(t0 + j) - 1u);
}
