#version 450
// Barycentric interpolation of the patch corners; blue, to show that this stage ran.

layout(triangles, equal_spacing, ccw) in;
layout(location = 0) out vec4 colour;

void main() {
  gl_Position = gl_TessCoord.x * gl_in[0].gl_Position + gl_TessCoord.y * gl_in[1].gl_Position +
                gl_TessCoord.z * gl_in[2].gl_Position;
  colour = vec4(0.0, 0.0, 1.0, 1.0);
}
