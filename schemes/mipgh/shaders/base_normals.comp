#version 450
// The normals the cpu takes from level 0 (vertex_tangents.h, regular_patches.h, facet_masks.h),
// written over the limit pass's after it: binding 0 holds level 0 as given here, not a level
// relative to the box's centre, so that the control points' differences are exact. One
// invocation per node:
// - kPart 0, D-vertices: the table's target D-vertex v, its terms (a control point, its weights
//   in T1 and T2) relative to v's own control point;
// - kPart 1, D-facet interiors, and 2, D-facet sides: per entry five words (the node weights'
//   offset in the weights for this level, the control points' offset, their count, side (| 4
//   where the D-edge runs against it), the first target node), weights per grid node (i, j)
//   row-major, `size` in T1 then `size` in T2, on the control points' differences from the first.
#include "mipgh.glsl"

layout(constant_id = 1) const uint kPart = 0u;

// lod.h's side_ij for a quad: node a of side k.
ivec2 side_ij(uint side, int n, int a) {
  if (side == 0u) return ivec2(0, a);
  if (side == 1u) return ivec2(a, n - 1);
  if (side == 2u) return ivec2(n - 1, n - 1 - a);
  return ivec2(n - 1 - a, 0);
}

void main() {
  const uint i = SDB_LINEAR_INVOCATION();
  if (i >= pc.count) return;
  precise vec3 t1 = vec3(0.0), t2 = vec3(0.0);
  uint target;
  if (kPart == 0u) {
    target = word(pc.table + i);
    const uint first = word(pc.begins + i), last = word(pc.begins + i + 1u);
    const vec3 c = node(target);  // D-vertex v is control point v
    for (uint j = first; j < last; ++j) {
      precise vec3 x = node(word(pc.sources + j)) - c;
      const int w = int(pc.weight_base + 2u * j);
      t1 += texelFetch(weights, w).x * x;
      t2 += texelFetch(weights, w + 1).x * x;
    }
  } else {
    const uint e = i / pc.per_item, k = i % pc.per_item, at = pc.table + 5u * e;
    const uint base = word(at), control = word(at + 1u), size = word(at + 2u), where = word(at + 3u);
    const int n = int(pc.n);
    ivec2 ij;
    if (kPart == 1u) {
      ij = ivec2(1 + int(k) / (n - 2), 1 + int(k) % (n - 2));
      target = word(at + 4u) + k;
    } else {
      ij = side_ij(where & 3u, n, 1 + int(k));
      target = word(at + 4u) + ((where & 4u) != 0u ? uint(n - 3) - k : k);
    }
    const uint w = base + uint(ij.x * n + ij.y) * 2u * size;
    const vec3 c = node(word(control));
    for (uint s = 1u; s < size; ++s) {
      precise vec3 x = node(word(control + s)) - c;
      t1 += texelFetch(weights, int(w + s)).x * x;
      t2 += texelFetch(weights, int(w + size + s)).x * x;
    }
  }
  store_normal(target, unit(t1, t2));
}
