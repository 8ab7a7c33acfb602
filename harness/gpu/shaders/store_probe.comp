#version 450
// The most a compute shader can write on the device (harness/bench/machine.cpp,
// measure_gpu_shader_write_bandwidth): vec4 stores, nothing computed. On lavapipe a storage-buffer
// store is a loop over the lanes and their components (harness/gpu/README.md, "Memory access on
// lavapipe"), where the buffer fill that measures the device's write bandwidth is one memset.
// The fastest form measured there: 8 consecutive elements per invocation, 256 invocations per
// work group (one element per invocation and 64 per group wrote 0.6 as much).
#extension GL_GOOGLE_include_directive : require
#include "sdb/dispatch.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = 0) restrict writeonly buffer Out { vec4 data[]; };

layout(push_constant) uniform Push {
  uint count;
  float value;
} pc;

void main() {
  const uint i = SDB_LINEAR_INVOCATION();
  const uint per_invocation = 8u, invocations = pc.count / per_invocation;
  if (i >= invocations) return;
  for (uint k = 0u; k < per_invocation; ++k) data[per_invocation * i + k] = vec4(pc.value, float(i), 0.0, 1.0);
}
