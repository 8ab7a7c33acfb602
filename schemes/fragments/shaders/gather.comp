#version 450
// Level 0: each fragment's control points, relative to the box's centre.
#include "fragments.glsl"

void main() {
  if (!begin_invocation()) return;
  const uint list = F[2u * g_fragment];
  const uvec2 range = chunk_of(T[limit_header() + kNumSlots0]);
  for (uint i = range.x; i < range.y; ++i) {
    const uint v = T[list + i];
    precise vec3 p = vec3(control[3u * v], control[3u * v + 1u], control[3u * v + 2u]) - pc.origin.xyz;
    store(i, p);
  }
}
