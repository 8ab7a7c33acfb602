#version 450
// mesh.vert with a colour per vertex: the deviation heat maps of the report's pictures.

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 colour;

layout(push_constant) uniform Push {
  mat4 mvp;
  vec4 view_rows[3];  // the view matrix's first three rows
  vec4 shading;       // x: ambient share of the brightness; the rest comes from the Lambert term
} pc;

layout(location = 0) out vec3 view_position;
layout(location = 1) out vec3 view_normal;
layout(location = 2) out vec3 vertex_colour;

void main() {
  vec4 p = vec4(position, 1.0);
  view_position = vec3(dot(pc.view_rows[0], p), dot(pc.view_rows[1], p), dot(pc.view_rows[2], p));
  view_normal = vec3(dot(pc.view_rows[0].xyz, normal), dot(pc.view_rows[1].xyz, normal), dot(pc.view_rows[2].xyz, normal));
  vertex_colour = colour;
  gl_Position = pc.mvp * p;
}
