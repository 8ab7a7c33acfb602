// cpatch-2pass, pass 2 (render mode): the paper's second pass, "instancing a (u, v)-grid on the
// vertex shader". An instance is a batch of kGridsPerInstance grids (one per quad; a one-batch
// index buffer), a vertex one grid sample: evaluate, transform for the rasterizer. Batching
// several small grids per instance keeps instances large enough to fill the vertex stage (one
// 5 x 5 grid per instance starves SIMD lanes, and lavapipe pays a fixed cost per instance).
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
layout(constant_id = 1) const int kGridsPerInstance = 1;
#include "evaluate.glsl"
#include "load_record.glsl"
#include "shading.glsl"

#if HEAT_MAP
layout(std430, binding = 4) restrict readonly buffer HeatValues { float heat_values[]; };
layout(location = 1) out vec3 colour;
#endif

layout(push_constant) uniform Push { int num_quads; } push;

void main() {
  const int quad = gl_InstanceIndex * kGridsPerInstance + gl_VertexIndex / kSamples;
  const int s = gl_VertexIndex % kSamples;
  if (quad >= push.num_quads) {  // the last batch's unused grids: every triangle degenerate
    gl_Position = vec4(0.0, 0.0, 0.5, 1.0);
    view_normal = vec3(0.0, 0.0, 1.0);
#if HEAT_MAP
    colour = vec3(0.0);
#endif
    return;
  }
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
