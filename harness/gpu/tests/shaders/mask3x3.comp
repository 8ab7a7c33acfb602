#version 450
// dst = 3x3 mask applied to src (edges clamped). `precise` forbids fusing the multiply and add
// into an FMA (SPIR-V NoContraction), and the loop order is fixed, so the result equals the CPU's
// separate multiply-then-add in the same order bit for bit: Vulkan requires float32 add and
// multiply to be correctly rounded.

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 0) readonly buffer Src { float src[]; };
layout(std430, binding = 1) writeonly buffer Dst { float dst[]; };

layout(push_constant) uniform Push {
  float weights[9];  // row by row, top row first
  uint width;
  uint height;
} pc;

void main() {
  uvec2 p = gl_GlobalInvocationID.xy;
  if (p.x >= pc.width || p.y >= pc.height) return;
  precise float sum = 0.0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      int x = clamp(int(p.x) + dx, 0, int(pc.width) - 1);
      int y = clamp(int(p.y) + dy, 0, int(pc.height) - 1);
      precise float product = pc.weights[(dy + 1) * 3 + (dx + 1)] * src[y * int(pc.width) + x];
      sum = sum + product;
    }
  }
  dst[p.y * pc.width + p.x] = sum;
}
