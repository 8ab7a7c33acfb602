#version 450
// Two `precise` functions called in an unrolled loop, four copies each: a multiply-add (which a
// device with FMA fuses unless told not to) and geometry-image's limit mask, 1/36 (16 c + 4 edges
// + corners) (which lavapipe's compiler reorders unless told not to). Every copy must keep
// NoContraction, so that each result equals the CPU's, operation by rounded operation.
// spirv-opt's -O (SPIRV-Tools 2022.4) kept it on the first unrolled copy only and turned the
// other multiply-adds into Fma instructions (cmake/Shaders.cmake).
#extension GL_EXT_control_flow_attributes : require

layout(local_size_x = 64) in;

// Per result: a, b, c for the multiply-add, then the limit mask's centre, four edge and four
// corner samples.
const uint kInputs = 12u;
layout(std430, binding = 0) readonly buffer Src { float src[]; };
layout(std430, binding = 1) writeonly buffer Dst { float dst[]; };  // per result: two floats

layout(push_constant) uniform Push {
  uint count;  // invocations, four results each
} pc;

float multiply_add(float a, float b, float c) {
  precise float r = a * b + c;
  return r;
}

float limit_mask(float centre, vec4 edge, vec4 corner) {
  precise float edges = (edge.x + edge.y) + (edge.z + edge.w);
  precise float corners = (corner.x + corner.y) + (corner.z + corner.w);
  precise float r = ((16.0 * centre + 4.0 * edges) + corners) * uintBitsToFloat(0x3ce38e39u);
  return r;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  float in_[4][12];
  [[unroll]] for (int k = 0; k < 4; ++k)
    [[unroll]] for (int q = 0; q < 12; ++q) in_[k][q] = src[(4u * i + uint(k)) * kInputs + uint(q)];
  float r[4][2];
  [[unroll]] for (int k = 0; k < 4; ++k) {
    r[k][0] = multiply_add(in_[k][0], in_[k][1], in_[k][2]);
    r[k][1] = limit_mask(in_[k][3], vec4(in_[k][4], in_[k][5], in_[k][6], in_[k][7]),
                         vec4(in_[k][8], in_[k][9], in_[k][10], in_[k][11]));
  }
  [[unroll]] for (int k = 0; k < 4; ++k)
    [[unroll]] for (int q = 0; q < 2; ++q) dst[(4u * i + uint(k)) * 2u + uint(q)] = r[k][q];
}
