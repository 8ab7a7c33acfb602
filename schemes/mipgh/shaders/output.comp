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
  if (kLimit) {
    const int at = int(3u * k);
    nrm = vec3(texelFetch(normals_in, at).x, texelFetch(normals_in, at + 1).x, texelFetch(normals_in, at + 2).x);
  }
  const int o = int(3u * (pc.scatter != 0u ? word(pc.scatter + i) : i));
  imageStore(out_position, o, vec4(p.x));
  imageStore(out_position, o + 1, vec4(p.y));
  imageStore(out_position, o + 2, vec4(p.z));
  imageStore(out_normal, o, vec4(nrm.x));
  imageStore(out_normal, o + 1, vec4(nrm.y));
  imageStore(out_normal, o + 2, vec4(nrm.z));
}
