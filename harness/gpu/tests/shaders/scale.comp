#version 450
// data *= factor, with the factor a specialization constant.

layout(local_size_x = 64) in;
layout(constant_id = 0) const float factor = 1.0;

layout(std430, binding = 0) buffer Data { float data[]; };
layout(push_constant) uniform Push { uint count; } pc;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < pc.count) data[i] *= factor;
}
