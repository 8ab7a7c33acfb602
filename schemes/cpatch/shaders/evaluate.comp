#version 450
// cpatch-2pass, pass 2 (evaluate-only mode), shaped for SIMD lanes (README.md, "The evaluate
// pass"): one invocation per (quad, grid row j), neighbouring invocations on different quads of
// one kind and the same row, so that everything but the quad is the same across the lanes:
// - one pipeline per patch kind (kCpatch) and per kind of row (kBorderRow: rows 0 and N - 1,
//   whose positions all come from the border curves), so no lane branches on either;
// - the row's loop over i has the same bounds in every lane, the c-patch's pieces are visited as
//   the row's segments (piece 3, then 0 or 2, then 1), and the grid weights are fetched at the same
//   texel in every lane;
// - the record is read once per row through a texel buffer (a vector gather on lavapipe, where a
//   storage-buffer load goes lane by lane), and the bicubic patch's column curves at v_j are
//   evaluated once per row, as the CPU does.
// The arithmetic is evaluate.glsl's, operation for operation: outputs stay bit-identical to the
// CPU's.
#extension GL_GOOGLE_include_directive : require

#include "buffers.glsl"
// Float3 positions and normals of the output chunk (scalar block layout: a 12-byte stride), one vec3
// store per sample. Lavapipe stores lane by lane and component by component (README.md, "The
// evaluate pass"); bicubic rows stored pairs of samples as three 64-bit words until that turned out
// to cost time where LLVM targets AVX-512 (harness/gpu/README.md, "Memory access on lavapipe").
#extension GL_EXT_scalar_block_layout : require
layout(scalar, binding = 2) writeonly buffer OutPositions { vec3 out_positions[]; };
layout(scalar, binding = 3) writeonly buffer OutNormals { vec3 out_normals[]; };
layout(binding = 0) uniform samplerBuffer record_texels;  // conversion.h PatchRecord, a vec4 per entry
layout(binding = 1) uniform samplerBuffer grid_texels;    // vulkan_resources.cpp grid_table()
// Per quad of this dispatch: its index << 4 | forward_sides (vulkan_resources.cpp quad_lists()).
layout(std430, binding = 4) restrict readonly buffer QuadList { uint quad_list[]; };
#define RECORD_ENTRY(i) texelFetch(record_texels, i)
#define GRID_LOAD(i) texelFetch(grid_texels, i)
#include "record.glsl"

layout(constant_id = 0) const int kRate = 2;
layout(constant_id = 1) const bool kCpatch = false;
layout(constant_id = 2) const bool kBorderRow = false;
layout(local_size_x_id = 3) in;
#include "evaluate.glsl"
#include "load_record.glsl"

layout(push_constant) uniform Push {
  uint first_quad;   // of the output chunk: output vertex (q - first_quad) N^2 + j N + i
  uint list_offset;  // of this dispatch's quads in quad_list
  uint count;        // quads in this dispatch
  uint first_row, row_step;  // row j = first_row + gl_WorkGroupID.x row_step
} push;

const int kLast = kRate - 1;

void store_sample(int index, vec3 position, SurfacePoint p) {
  out_positions[index] = position;
  out_normals[index] = unit_normal(p.du, p.dv);
}

// The position of sample (i, j), 0 < i < N - 1, from the patch point: on a border row the side's
// curve (write_border), else p*_0 + the patch.
vec3 row_position(vec3 record[kRecordSize], uint forward_sides, int i, int j, vec3 patch_position) {
  if (kBorderRow) return j == 0 ? border_position(record, forward_sides, 0, i) : border_position(record, forward_sides, 2, kLast - i);
  precise vec3 p = record[record_index(0, kP)] + patch_position;
  return p;
}

// Sample i of a bicubic row: the row's ends (i = 0, N - 1) are end_p and end_n, computed apart.
void bicubic_sample(vec3 column[4], vec3 column_dv[4], vec3 record[kRecordSize], uint forward_sides, int i, int j,
                    vec3 end_p[2], vec3 end_n[2], out vec3 position, out vec3 normal) {
  const SurfacePoint p = bicubic_along_row(column, column_dv, i);
  position = row_position(record, forward_sides, i, j, p.position);
  normal = unit_normal(p.du, p.dv);
  if (i == 0) position = end_p[0], normal = end_n[0];
  if (i == kLast) position = end_p[1], normal = end_n[1];
}

// The row's samples in order, its ends (computed once, before the loop) included.
void bicubic_row(PatchControl c, vec3 record[kRecordSize], uint forward_sides, int j, int first) {
  vec3 column[4], column_dv[4];
  bicubic_columns(c, j, column, column_dv);
  vec3 end_p[2], end_n[2];
  [[unroll]] for (int end = 0; end < 2; ++end) {
    const int i = end * kLast;
    const SurfacePoint p = bicubic_along_row(column, column_dv, i);
    end_p[end] = sample_position(record, forward_sides, i, j, p.position);
    end_n[end] = unit_normal(p.du, p.dv);
  }
  for (int i = 0; i < kRate; ++i) {
    vec3 p, n;
    bicubic_sample(column, column_dv, record, forward_sides, i, j, end_p, end_n, p, n);
    out_positions[first + i] = p;
    out_normals[first + i] = n;
  }
}

// Samples [begin, end) of row j, all in piece `piece`.
void cpatch_segment(PatchControl c, vec3 record[kRecordSize], uint forward_sides, int j, int first, int piece, int begin,
                    int end) {
  if (begin >= end) return;
  vec3 b[15];
  piece_points(c, piece, b);
  for (int i = begin; i < end; ++i) {
    const SurfacePoint p = cpatch_point(b, j * kRate + i);
    store_sample(first + i, row_position(record, forward_sides, i, j, p.position), p);
  }
}

// Row j meets piece 3 on [0, lo), piece 0 (lower half) or 2 (upper half) up to the other
// diagonal, piece 1 after it (cpatch_piece(), ties included); the row's end samples are done apart.
void cpatch_row(PatchControl c, vec3 record[kRecordSize], uint forward_sides, int j, int first) {
  const bool lower = j <= kLast - j;
  const int lo = min(j, kLast - j);
  const int hi = lower ? kLast - j + 1 : j;  // first sample of piece 1
  cpatch_segment(c, record, forward_sides, j, first, 3, 1, max(lo, 1));
  cpatch_segment(c, record, forward_sides, j, first, lower ? 0 : 2, max(lo, 1), min(hi, kLast));
  cpatch_segment(c, record, forward_sides, j, first, 1, max(hi, 1), kLast);
  [[unroll]] for (int end = 0; end < 2; ++end) {
    const int i = end * kLast;
    const SurfacePoint p = evaluate_cpatch(c, i, j);
    store_sample(first + i, sample_position(record, forward_sides, i, j, p.position), p);
  }
}

void main() {
  // Rows vary fastest across work groups: lavapipe runs groups in x, y, z order, so a lane writes its
  // quad's rows one after another, a stream where rows apart in time were cache misses each.
  const uint slot = (gl_WorkGroupID.z * gl_NumWorkGroups.y + gl_WorkGroupID.y) * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
  // Past the last quad a lane repeats it (same values to the same place): no lane leaves early.
  const uint entry = quad_list[push.list_offset + min(slot, push.count - 1u)];
  const int quad = int(entry >> 4u);
  const uint forward_sides = entry & 15u;
  const int j = int(push.first_row + gl_WorkGroupID.x * push.row_step);
  vec3 record[kRecordSize];
  load_record(quad, kCpatch, record);
  const PatchControl c = local_control(record);
  const int first = (quad - int(push.first_quad)) * kSamples + j * kRate;
  if (kCpatch)
    cpatch_row(c, record, forward_sides, j, first);
  else
    bicubic_row(c, record, forward_sides, j, first);
}
