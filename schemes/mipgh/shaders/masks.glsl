// The nodes the stencils leave to the mesh shader's masks (mask_table.h): every D-vertex and the
// nodes of tagged, boundary or mixed D-edges, one invocation each, summing its weighted source
// nodes; the limit's three masks (position, T1, T2) at once. In double where the device has it
// (masks_double.comp), as the cpu's shader sums them: a crease's or a valence-2 vertex's tangent
// masks cancel, and summed in float their normals turn by up to 0.04 degrees.
#include "mipgh.glsl"

layout(constant_id = 1) const bool kLimit = false;

#ifdef SDB_DOUBLE
#define REAL dvec3
#else
#define REAL vec3
#endif

void main() {
  const uint i = SDB_LINEAR_INVOCATION();
  if (i >= pc.count) return;
  const uint target = word(pc.table + i), first = word(pc.begins + i), last = word(pc.begins + i + 1u);
  precise REAL p = REAL(0.0), t1 = REAL(0.0), t2 = REAL(0.0);
  for (uint j = first; j < last; ++j) {
    const REAL x = REAL(node(word(pc.sources + j)));
    if (kLimit) {
      const int w = int(pc.weight_base + 3u * j);
      p += texelFetch(weights, w).x * x;
      t1 += texelFetch(weights, w + 1).x * x;
      t2 += texelFetch(weights, w + 2).x * x;
    } else {
      p += texelFetch(weights, int(pc.weight_base + j)).x * x;
    }
  }
  store(target, vec3(p));
  if (kLimit) store_normal(target, unit(vec3(t1), vec3(t2)));
}
