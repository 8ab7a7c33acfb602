#version 450
// cpatch-tess, tessellation control stage: assembles the quad's patch (Figure 6 / Table 2) from
// its four corners (corner.vert) and asks the tessellator for the N x N grid: equal spacing with
// every outer and inner level N - 1 gives the samples u_i = i / (N - 1) (patch_body.glsl checks
// that it does). Output vertex k carries corner k's seven record entries.
#extension GL_GOOGLE_include_directive : require

// Bindings 0-5 are corner.vert's.
#define BINDING_QUAD_INFO 6
#define BINDING_CORNER_WEIGHTS 7
#include "buffers.glsl"
#include "record.glsl"
#include "table2.glsl"
#include "corner_inputs.glsl"

layout(constant_id = 0) const int kRate = 2;
layout(vertices = 4) out;

layout(location = 0) out vec3 record_p[];
layout(location = 1) out vec3 record_v[];
layout(location = 2) out vec3 record_t0[];
layout(location = 3) out vec3 record_t1[];
layout(location = 4) out vec3 record_x0[];
layout(location = 5) out vec3 record_x1[];
layout(location = 6) out vec3 record_x2[];
layout(location = 7) patch out int patch_quad;

void main() {
  const int quad = corner_quad[0];
  CornerData corner[4];
  read_corners(corner);
  // Table 2 couples all four corners: every invocation assembles the whole record (the same
  // operations, hence the same bits) and hands on its own corner's part.
  vec3 record[kRecordSize];
  build_record(corner, cpatch_index_of(quad_info[quad]), record);
  const int k = gl_InvocationID;
  record_p[gl_InvocationID] = CORNER_ENTRY(record, k, kP);
  record_v[gl_InvocationID] = CORNER_ENTRY(record, k, kV);
  record_t0[gl_InvocationID] = CORNER_ENTRY(record, k, kT0);
  record_t1[gl_InvocationID] = CORNER_ENTRY(record, k, kT1);
  record_x0[gl_InvocationID] = CORNER_ENTRY(record, k, kX0);
  record_x1[gl_InvocationID] = CORNER_ENTRY(record, k, kX1);
  record_x2[gl_InvocationID] = CORNER_ENTRY(record, k, kX2);
  if (k == 0) {
    patch_quad = quad;
    const float level = float(kRate - 1);
    gl_TessLevelOuter[0] = level;
    gl_TessLevelOuter[1] = level;
    gl_TessLevelOuter[2] = level;
    gl_TessLevelOuter[3] = level;
    gl_TessLevelInner[0] = level;
    gl_TessLevelInner[1] = level;
  }
}
