#version 450
// Level 0: each fragment's control points, relative to the box's centre; and relative to its
// first control point, for the limit's net normals.
#include "fragments.glsl"

void main() {
  if (!begin_invocation()) return;
  const uint list = fragment_word(3u * g_fragment);
  const vec3 first = control_point(table_word(list));
  const uvec2 range = chunk_of(table_word(limit_header() + kNumSlots0));
  for (uint i = range.x; i < range.y; ++i) {
    const vec3 c = control_point(table_word(list + i));
    precise vec3 p = c - pc.origin.xyz;
    store(i, p);
    precise vec3 q = c - first;
    store_net(i, q);
  }
}
