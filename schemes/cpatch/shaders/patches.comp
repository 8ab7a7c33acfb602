#version 450
// cpatch-2pass, pass 1b: Figure 6 / Table 2 per quad, one invocation per quad, streaming out the
// quad's patch record (the paper's 16 or 24 coefficients, plus the corner points that anchor the
// relative coordinates: conversion.h PatchRecord).
#extension GL_GOOGLE_include_directive : require
#include "sdb/dispatch.glsl"

#define BINDING_CONTROL_POINTS 0
#define BINDING_CORNERS 1
#define BINDING_QUAD_INFO 2
#define BINDING_CORNER_WEIGHTS 3
#define BINDING_LIMIT 4  // and 5, 6, 7: face, edge, tangent points
#define BINDING_RECORDS 8
#define RECORDS_WRITTEN
#include "buffers.glsl"
#include "record.glsl"
#include "table2.glsl"

layout(local_size_x = 64) in;
layout(push_constant) uniform Push { uint num_quads; } push;

// A corner's Table 1 points, as pass 1a wrote them.
CornerData corner_from_vertex_points(QuadCorner corner) {
  CornerData c;
  c.p = LOAD3(control_points, corner.vertex);
  c.v = LOAD3(limit_points, corner.vertex);
  c.t0 = LOAD3(tangent_points, corner.sector_slot);
  c.t1 = LOAD3(tangent_points, corner.prev_edge_slot);
  c.f = LOAD3(face_points, corner.sector_slot);
  c.e0 = LOAD3(edge_points, corner.sector_slot);
  c.e1 = LOAD3(edge_points, corner.prev_edge_slot);
  return c;
}

void main() {
  const uint quad = SDB_LINEAR_INVOCATION();
  if (quad >= push.num_quads) return;
  CornerData corner[4];
  [[unroll]] for (int i = 0; i < 4; ++i) corner[i] = corner_from_vertex_points(corners[4 * quad + i]);
  vec3 record[kRecordSize];
  build_record(corner, cpatch_index_of(quad_info[quad]), record);
  const bool is_cpatch = cpatch_index_of(quad_info[quad]) >= 0;
  [[unroll]] for (int e = 0; e < kRecordSize; ++e) {
    // An ordinary quad's record is 16 coefficients and 4 corner points: skip X1, X2.
    if (!is_cpatch && e % 7 > kX0) continue;
    records[int(quad) * kRecordSize + e] = vec4(record[e], 0.0);
  }
}
