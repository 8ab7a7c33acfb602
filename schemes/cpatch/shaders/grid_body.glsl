// cpatch-2pass, pass 2 (render mode): the paper's second pass, "instancing a (u, v)-grid on the
// vertex shader". One instance per quad (gl_InstanceIndex), one vertex per grid sample
// (gl_VertexIndex, through a one-quad index buffer): evaluate, transform for the rasterizer.
// Included by grid.vert (HEAT_MAP 0) and grid_heat.vert (HEAT_MAP 1: colour by a per-output-vertex
// value, for the deviation heat maps).
#extension GL_GOOGLE_include_directive : require

#define BINDING_RECORDS 0
#define BINDING_QUAD_INFO 1
#define BINDING_GRID 2
#define BINDING_CAMERA 3
#include "buffers.glsl"
#include "record.glsl"

layout(constant_id = 0) const int kRate = 2;
#include "evaluate.glsl"
#include "load_record.glsl"
#include "shading.glsl"

#if HEAT_MAP
layout(std430, binding = 4) restrict readonly buffer HeatValues { float heat_values[]; };
layout(location = 1) out vec3 colour;
#endif

void main() {
  const int quad = gl_InstanceIndex, s = gl_VertexIndex;
  const uint info = quad_info[quad];
  vec3 record[kRecordSize];
  load_record(quad, cpatch_index_of(info) >= 0, record);
  vec3 position, normal;
  evaluate_sample(record, cpatch_index_of(info) >= 0, forward_sides_of(info), s % kRate, s / kRate, position, normal);
  gl_Position = clip_position(position);
  view_normal = to_view(normal);
#if HEAT_MAP
  colour = heat_colour(heat_values[quad * kSamples + s] / camera.heat_scale.x);
#endif
}
