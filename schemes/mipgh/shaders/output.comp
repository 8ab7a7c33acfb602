#version 450
// The output: level d's nodes (or the limit's, picked from a deeper level where semi-sharp creases
// outlast the depth), moved back from the box's centre, and their normals (zero without a limit);
// adaptive, one level's drawn nodes, each to its own output slot.
#include "mipgh.glsl"

layout(constant_id = 1) const bool kLimit = true;

void main() {
  const uint i = SDB_LINEAR_INVOCATION();
  if (i >= pc.count) return;
  const uint k = pc.pick == 0xffffffffu ? i : word(pc.pick + i);
  precise vec3 p = node(k) + pc.origin.xyz;
  vec3 nrm = vec3(0.0);
  if (kLimit) nrm = texelFetch(normals_in, int(k)).xyz;
  store_output(pc.scatter != 0u ? word(pc.scatter + i) : i, p, nrm);
}
