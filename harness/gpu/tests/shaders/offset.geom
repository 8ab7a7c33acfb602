#version 450
// Emits each triangle twice, green: in place and shifted right by 1 in clip space.

layout(triangles) in;
layout(triangle_strip, max_vertices = 6) out;
layout(location = 0) out vec4 colour;

void main() {
  for (int copy = 0; copy < 2; ++copy) {
    for (int i = 0; i < 3; ++i) {
      gl_Position = gl_in[i].gl_Position + vec4(float(copy), 0.0, 0.0, 0.0);
      colour = vec4(0.0, 1.0, 0.0, 1.0);
      EmitVertex();
    }
    EndPrimitive();
  }
}
