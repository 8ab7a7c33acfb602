#version 450
// Heat map: the per-vertex colour (grid_heat.vert), lightly shaded to keep the shape readable.
layout(location = 0) in vec3 view_normal;
layout(location = 1) in vec3 colour;
layout(location = 0) out vec4 out_colour;

void main() {
  const float lambert = abs(normalize(view_normal).z);
  out_colour = vec4(colour * (0.55 + 0.45 * lambert), 1.0);
}
