#version 450
// mesh.frag's two-sided headlight Lambert on an interpolated vertex colour: a surface coloured by
// a scalar still shows its shape.

layout(push_constant) uniform Push {
  mat4 mvp;
  vec4 view_rows[3];
  vec4 shading;
} pc;

layout(location = 0) in vec3 view_position;
layout(location = 1) in vec3 view_normal;
layout(location = 2) in vec3 vertex_colour;
layout(location = 0) out vec4 out_colour;

void main() {
  vec3 to_eye = normalize(-view_position);
  float lambert = abs(dot(normalize(view_normal), to_eye));
  float ambient = pc.shading.x;
  out_colour = vec4(vertex_colour * (ambient + (1.0 - ambient) * lambert), 1.0);
}
