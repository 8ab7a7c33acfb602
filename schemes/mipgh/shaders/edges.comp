#version 450
// The D-edge visit of a step (its edge points or its vertex points; a pipeline each) or the limit
// projection of its nodes, for the fast D-edges (untagged, two D-facets of one kind): one
// invocation per target node, reading the strip's nodes it needs (processor.cpp's Strip: a on the
// edge, b one in from the major side, c one in from the minor side) through the side rows. The
// table holds per fast D-edge: its first node at the target level, the major D-facet and its side
// kind, the minor's.
#include "mipgh.glsl"

layout(constant_id = 1) const bool kQuad = true;
layout(constant_id = 2) const uint kPart = 0u;
const uint kEdgePoints = 0u, kVertexPoints = 1u, kLimit = 2u;

uint g_major, g_minor, g_on, g_in, g_across, g_last;
// side_rows(sigma, size, side, depth) as processor.cpp lays them out: (kind * 2 + depth) * n.
uint row(uint kind, uint depth) { return pc.rows + (kind * 2u + depth) * pc.n; }
vec3 A(uint t) { return node(texelFetch(lod, int(g_major + word(g_on + t))).x); }
vec3 B(uint t) { return node(texelFetch(lod, int(g_major + word(g_in + t))).x); }
vec3 C(uint t) { return node(texelFetch(lod, int(g_minor + word(g_across + g_last - t))).x); }

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
  precise vec3 p;
  if (kPart == kEdgePoints) {
    const uint t = k;
    if (kQuad) p = 0.375 * (A(t) + A(t + 1u)) + 0.0625 * ((B(t) + B(t + 1u)) + (C(t) + C(t + 1u)));
    else p = 0.375 * (A(t) + A(t + 1u)) + 0.125 * (B(t) + C(t));
    store(edge + 2u * t, p);
    return;
  }
  const uint t = k + 1u;
  if (kPart == kVertexPoints) {
    if (kQuad) {
      p = 0.5625 * A(t) + 0.09375 * ((A(t + 1u) + A(t - 1u)) + (B(t) + C(t))) +
          0.015625 * ((B(t + 1u) + C(t - 1u)) + (B(t - 1u) + C(t + 1u)));
    } else {
      p = 0.625 * A(t) + 0.0625 * (((A(t + 1u) + A(t - 1u)) + (B(t) + C(t - 1u))) + (B(t - 1u) + C(t)));
    }
    store(edge + 2u * t - 1u, p);
    return;
  }
  // the limit, the ring counter-clockwise seen from the major D-facet (processor.cpp, project_edge)
  precise vec3 t1, t2;
  if (kQuad) {
    const vec3 c = A(t), e0 = A(t + 1u), e1 = B(t), e2 = A(t - 1u), e3 = C(t);
    const vec3 d0 = B(t + 1u), d1 = B(t - 1u), d2 = C(t - 1u), d3 = C(t + 1u);
    p = (1.0 / 36.0) * (16.0 * c + 4.0 * ((e0 + e2) + (e1 + e3)) + ((d0 + d2) + (d1 + d3)));
    t1 = 4.0 * (e0 - e2) + ((d0 + d3) - (d1 + d2));
    t2 = 4.0 * (e1 - e3) + ((d0 + d1) - (d2 + d3));
  } else {
    const vec3 c = A(t), e0 = A(t + 1u), e1 = B(t), e2 = B(t - 1u), e3 = A(t - 1u), e4 = C(t - 1u), e5 = C(t);
    p = 0.5 * c + (1.0 / 12.0) * (((e0 + e3) + (e1 + e4)) + (e2 + e5));
    t1 = (e0 - e3) + 0.5 * ((e1 - e2) - (e4 - e5));
    t2 = (e1 + e2) - (e4 + e5);
  }
  store(edge + t - 1u, p);
  store_normal(edge + t - 1u, unit(t1, t2));
}
