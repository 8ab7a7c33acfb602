#version 450
// Without the limit projection (the uniform-refinement peers' tests compare the refined level with
// Far's refinement): the last level's points moved back from the control box's centre, as packed xyz into the output.
#extension GL_GOOGLE_include_directive : require
#include "sdb/dispatch.glsl"

layout(local_size_x_id = 0) in;
layout(binding = 0) uniform samplerBuffer points;
layout(binding = 1, r32f) uniform restrict writeonly imageBuffer out_position;
layout(push_constant) uniform Push {
  uint count, pad0, pad1, pad2;
  vec4 origin;
} pc;

void main() {
  const uint v = SDB_LINEAR_INVOCATION();
  if (v >= pc.count) return;
  precise vec3 p = texelFetch(points, int(v)).xyz + pc.origin.xyz;
  imageStore(out_position, int(3u * v), vec4(p.x));
  imageStore(out_position, int(3u * v + 1u), vec4(p.y));
  imageStore(out_position, int(3u * v + 2u), vec4(p.z));
}
