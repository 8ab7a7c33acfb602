// What the limit passes share (limit_vulkan.h): the bindings and push constants, the point fetch
// and the output stores. The arithmetic is limit.cpp's, operation for operation and `precise`.
#extension GL_GOOGLE_include_directive : require
#include "sdb/dispatch.glsl"

layout(local_size_x_id = 0) in;

layout(binding = 0) uniform samplerBuffer points;           // the level's points, xyz of rgba32f texels
layout(binding = 1) uniform usamplerBuffer regular_ring;    // per vertex from pc.first, ring_size entries (kNone first: special)
layout(binding = 2) uniform usamplerBuffer special;         // the special vertices
layout(binding = 3) uniform usamplerBuffer begin;           // their entries' ranges
layout(binding = 4) uniform usamplerBuffer ring;            // the entries' vertices
layout(binding = 5) uniform samplerBuffer weights;          // and weights, three an entry
layout(binding = 6, r32f) uniform restrict writeonly imageBuffer out_position;  // packed xyz
layout(binding = 7, r32f) uniform restrict writeonly imageBuffer out_normal;

layout(push_constant) uniform Push {
  uint count;      // vertices (regular pass: from `first`, one view of the rings) or special vertices (special pass)
  uint ring_size;  // 8 (Catmull-Clark) or 6 (Loop)
  uint first;      // the regular pass: the first vertex of this dispatch and of its view of the rings
  uint pad;
  vec4 origin;     // added to every position
  vec4 k;          // the regular masks' constants from the CPU (GLSL's constant division is not C++'s)
} pc;

const uint kNone = 0xffffffffu;

vec3 point(uint v) { return texelFetch(points, int(v)).xyz; }

precise vec3 unit_normal(vec3 a, vec3 b) {
  precise vec3 c = vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
  precise float len2 = c.x * c.x + c.y * c.y + c.z * c.z;
  precise float k = len2 > 0.0 ? 1.0 / sqrt(len2) : 0.0;
  precise vec3 n = c * k;
  return n;
}

void store(uint v, vec3 p, vec3 n) {
  const int o = int(3u * v);
  imageStore(out_position, o, vec4(p.x));
  imageStore(out_position, o + 1, vec4(p.y));
  imageStore(out_position, o + 2, vec4(p.z));
  imageStore(out_normal, o, vec4(n.x));
  imageStore(out_normal, o + 1, vec4(n.y));
  imageStore(out_normal, o + 2, vec4(n.z));
}
