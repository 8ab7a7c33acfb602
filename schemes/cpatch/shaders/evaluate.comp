#version 450
// cpatch-2pass, pass 2 (evaluate-only mode): one invocation per grid row of a quad (N output
// vertices) in one chunk (gpu::plan_chunks), writing float3 positions and unit normals. Output
// vertex k is grid sample (i, j) = (s mod N, s div N), s = k mod N^2, of quad k div N^2. A row
// per invocation reads the quad's record once for N samples: the record loads are what a
// sample costs most on lavapipe, and N x quads invocations still fill a GPU.
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
  uint first_row;  // of this chunk, in the whole output: quad q's row j is row q N + j
  uint rows;       // in this chunk
} push;

void main() {
  const uint local_row = SDB_LINEAR_INVOCATION();
  if (local_row >= push.rows) return;
  const uint row = push.first_row + local_row;
  const int quad = int(row / uint(kRate)), j = int(row % uint(kRate));
  const uint info = quad_info[quad];
  const bool is_cpatch = cpatch_index_of(info) >= 0;
  vec3 record[kRecordSize];
  load_record(quad, is_cpatch, record);
  for (int i = 0; i < kRate; ++i) {
    vec3 position, normal;
    evaluate_sample(record, is_cpatch, forward_sides_of(info), i, j, position, normal);
    const int local = int(local_row) * kRate + i;  // chunk-relative vertex
    STORE3(out_positions, local, position);
    STORE3(out_normals, local, normal);
  }
}
