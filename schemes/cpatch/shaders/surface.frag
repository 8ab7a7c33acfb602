#version 450
// Lambert under a light at the eye, two-sided; the light direction is the view axis, so that the
// pre-rasterization stages need hand over only the view-space normal (shading.glsl).
layout(location = 0) in vec3 view_normal;
layout(location = 0) out vec4 out_colour;

void main() {
  const vec3 base = vec3(0.80, 0.72, 0.60);
  const float lambert = abs(normalize(view_normal).z);
  out_colour = vec4(base * (0.15 + 0.85 * lambert), 1.0);
}
