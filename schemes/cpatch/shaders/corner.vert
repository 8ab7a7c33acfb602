#version 450
// cpatch-1pass and cpatch-tess, vertex stage: Table 1 for one quad corner (vertex index 4 q + i,
// a non-indexed draw), handing the geometry or tessellation control stage the corner's p* and,
// relative to it, v, t_0, t_1, f, e_0, e_1 (record.glsl's CornerData). Every corner of a vertex
// computes its neighbourhood again (the paper's 1-pass vertex shader works per vertex; a vertex
// shader output cannot carry a valence-long list of points), with the same operations, so the
// points agree bit for bit with each other and with the CPU's.
#extension GL_GOOGLE_include_directive : require

#define BINDING_CONTROL_POINTS 0
#define BINDING_FIRST_SLOT 1
#define BINDING_RING 2
#define BINDING_VALENCE_CONSTANTS 3
#define BINDING_TRIG 4
#define BINDING_CORNERS 5
#include "buffers.glsl"
#include "record.glsl"
#include "table1.glsl"

layout(location = 0) out vec3 corner_p;
layout(location = 1) out vec3 corner_v;
layout(location = 2) out vec3 corner_t0;
layout(location = 3) out vec3 corner_t1;
layout(location = 4) out vec3 corner_f;
layout(location = 5) out vec3 corner_e0;
layout(location = 6) out vec3 corner_e1;
// The quad, for the patch stages: gl_PrimitiveID there is not reliable across a large draw (on
// lavapipe the tessellation stages' count restarts every 1024 patches).
layout(location = 7) flat out int corner_quad;

void main() {
  const CornerData c = corner_data(corners[gl_VertexIndex]);
  corner_p = c.p;
  corner_v = c.v;
  corner_t0 = c.t0;
  corner_t1 = c.t1;
  corner_f = c.f;
  corner_e0 = c.e0;
  corner_e1 = c.e1;
  corner_quad = gl_VertexIndex / 4;
}
