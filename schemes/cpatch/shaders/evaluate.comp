#version 450
// cpatch-2pass, pass 2 (evaluate-only mode): one invocation per output vertex of one chunk
// (gpu::plan_chunks), writing float3 position and unit normal. Output vertex k is grid sample
// (i, j) = (s mod N, s div N), s = k mod N^2, of quad k div N^2.
#extension GL_GOOGLE_include_directive : require
#include "sdb/dispatch.glsl"

#define BINDING_RECORDS 0
#define BINDING_QUAD_INFO 1
#define BINDING_GRID 2
#define BINDING_OUTPUT 3  // and 4: normals
#include "buffers.glsl"
#include "record.glsl"

layout(constant_id = 0) const int kRate = 2;
#include "evaluate.glsl"
#include "load_record.glsl"

layout(local_size_x = 64) in;
layout(push_constant) uniform Push {
  uint first_element;  // of this chunk, in the whole output
  uint elements;       // in this chunk
} push;

void main() {
  const uint local = SDB_LINEAR_INVOCATION();
  if (local >= push.elements) return;
  const uint element = push.first_element + local;
  const uint quad = element / uint(kSamples);
  const int s = int(element % uint(kSamples));
  const uint info = quad_info[quad];
  vec3 record[kRecordSize];
  load_record(int(quad), cpatch_index_of(info) >= 0, record);
  vec3 position, normal;
  evaluate_sample(record, cpatch_index_of(info) >= 0, forward_sides_of(info), s % kRate, s / kRate, position, normal);
  STORE3(out_positions, local, position);
  STORE3(out_normals, local, normal);
}
