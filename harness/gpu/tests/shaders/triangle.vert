#version 450
// A 2D triangle in clip space, shifted by instance; red, so later stages show by changing colour.

layout(location = 0) in vec2 position;
layout(push_constant) uniform Push { vec2 instance_offset; } pc;
layout(location = 0) out vec4 colour;

void main() {
  gl_Position = vec4(position + float(gl_InstanceIndex) * pc.instance_offset, 0.5, 1.0);
  colour = vec4(1.0, 0.0, 0.0, 1.0);
}
