#version 450
// Evaluate-only mode of cpatch-1pass and cpatch-tess: nothing reaches the rasterizer (the geometry
// stage emits no vertex, the tessellation stage places its vertices outside the clip volume), but
// a graphics pipeline needs a fragment stage; this one takes no inputs from them.
layout(location = 0) out vec4 out_colour;

void main() { out_colour = vec4(1.0); }
