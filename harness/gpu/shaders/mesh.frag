#version 450
// Headlight Lambert: the light sits at the eye. Two-sided (abs), so that a mesh with flipped
// orientation still shows its shape.

layout(push_constant) uniform Push {
  mat4 mvp;
  vec4 view_rows[3];
  vec4 colour;
} pc;

layout(location = 0) in vec3 view_position;
layout(location = 1) in vec3 view_normal;
layout(location = 0) out vec4 out_colour;

void main() {
  vec3 to_eye = normalize(-view_position);
  float lambert = abs(dot(normalize(view_normal), to_eye));
  out_colour = vec4(pc.colour.rgb * (0.15 + 0.85 * lambert), 1.0);
}
