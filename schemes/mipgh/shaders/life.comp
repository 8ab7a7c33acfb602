#version 450
// The game of life's mesh shader (life.h) on the device: each node's new state from its 1-disk's
// live nodes (the neighbour lists the cpu processor gathered), rule B3/S23; a node in no face
// keeps its state (as MeshProcessor::adjust copies it).
#extension GL_GOOGLE_include_directive : require
#include "sdb/dispatch.glsl"

layout(local_size_x = 64) in;
layout(binding = 0) uniform samplerBuffer state_in;
layout(binding = 1, r32f) uniform restrict writeonly imageBuffer state_out;
layout(binding = 2) uniform usamplerBuffer words;  // per node its list's start (nodes + 1), then the lists
layout(push_constant) uniform Push {
  uint nodes;
  uint lists;  // the first list's word
} pc;

void main() {
  const uint i = SDB_LINEAR_INVOCATION();
  if (i >= pc.nodes) return;
  const uint first = texelFetch(words, int(i)).x, last = texelFetch(words, int(i + 1u)).x;
  const bool was = texelFetch(state_in, int(i)).x > 0.5;
  uint alive = 0u;
  for (uint j = first; j < last; ++j) alive += texelFetch(state_in, int(texelFetch(words, int(pc.lists + j)).x)).x > 0.5 ? 1u : 0u;
  const bool now = first == last ? was : alive == 3u || (was && alive == 2u);
  imageStore(state_out, int(i), vec4(now ? 1.0 : 0.0));
}
