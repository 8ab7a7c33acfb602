#version 450
// Level 0: each fragment's control points, relative to the box's centre.
#include "fragments.glsl"

void main() {
  if (!begin_invocation()) return;
  const uint list = fragment_word(2u * g_fragment);
  const uvec2 range = chunk_of(table_word(limit_header() + kNumSlots0));
  for (uint i = range.x; i < range.y; ++i) {
    const uint v = table_word(list + i);
    precise vec3 p = vec3(control_float(3u * v), control_float(3u * v + 1u), control_float(3u * v + 2u)) - pc.origin.xyz;
    store(i, p);
  }
}
