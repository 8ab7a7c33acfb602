#version 450
// The first Catmull-Clark step (first_step.cpp, apply_stencils): one level-1 point an invocation,
// its stencil's weighted sum of the control points in the table's order.
#extension GL_GOOGLE_include_directive : require
#include "sdb/dispatch.glsl"

layout(local_size_x_id = 0) in;
layout(binding = 0) uniform samplerBuffer control;                      // relative to the box's centre
layout(binding = 1, rgba32f) uniform restrict writeonly imageBuffer dst;  // level 1's points
layout(binding = 2) uniform usamplerBuffer begin_of;
layout(binding = 3) uniform usamplerBuffer source_of;
layout(binding = 4) uniform samplerBuffer weight_of;
layout(binding = 5) uniform usamplerBuffer out_index;  // (flags & kOutIndex) only

layout(push_constant) uniform Push {
  uint count;  // rows
  uint flags;
} pc;

const uint kNone = 0xffffffffu;
const uint kOutIndex = 4u;  // vulkan.cpp

void main() {
  const uint r = SDB_LINEAR_INVOCATION();
  if (r >= pc.count) return;
  const uint to = (pc.flags & kOutIndex) != 0u ? texelFetch(out_index, int(r)).x : r;
  if (to == kNone) return;
  precise float x = 0.0, y = 0.0, z = 0.0;
  const uint last = texelFetch(begin_of, int(r + 1u)).x;
  for (uint i = texelFetch(begin_of, int(r)).x; i < last; ++i) {
    const vec3 p = texelFetch(control, int(texelFetch(source_of, int(i)).x)).xyz;
    const float w = texelFetch(weight_of, int(i)).x;
    x = x + p.x * w, y = y + p.y * w, z = z + p.z * w;
  }
  imageStore(dst, int(to), vec4(x, y, z, 0.0));
}
