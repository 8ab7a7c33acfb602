#version 450
// Writes a hash of each element's index in the whole output into one chunk of it: the chunk's
// binding starts at element `first`.
#extension GL_GOOGLE_include_directive : require
#include "sdb/dispatch.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = 0) writeonly buffer Out { uint data[]; };

layout(push_constant) uniform Push {
  uint first;
  uint count;
} pc;

void main() {
  uint i = SDB_LINEAR_INVOCATION();
  if (i >= pc.count) return;
  uint index = pc.first + i;
  data[i] = (index * 2654435761u) ^ 0x9E3779B9u;
}
