// cpatch-1pass, geometry stage: the paper's 1-pass scheme (Section 4, Figure 11). One invocation
// per quad (a lines-with-adjacency primitive of its four corners, from corner.vert) assembles the
// patch (Figure 6 / Table 2) and evaluates it on the N x N grid:
//   STORE_OUTPUT 0 (render mode): emits N - 1 triangle strips of 2 N vertices, i.e. 2 N (N - 1)
//     vertices of 7 components (clip position, view normal): the device's geometry output limits
//     bound N (vulkan.cpp, onepass_max_rate());
//   STORE_OUTPUT 1 (evaluate-only mode): stores the N^2 positions and normals into the output
//     buffers (vertexPipelineStoresAndAtomics) and emits nothing. It declares the same
//     max_vertices, so that both modes are the same stage with the same limit.
// A wrapper defines RATE (N, compile-time: max_vertices must be a literal) and STORE_OUTPUT.
#extension GL_GOOGLE_include_directive : require

// Bindings 0-5 are corner.vert's.
#define BINDING_QUAD_INFO 6
#define BINDING_CORNER_WEIGHTS 7
#define BINDING_GRID 8
#if STORE_OUTPUT
#define BINDING_OUTPUT 9  // and 10
#else
#define BINDING_CAMERA 9
#endif
#include "buffers.glsl"
#include "record.glsl"
#include "table2.glsl"

layout(lines_adjacency) in;  // before the corner inputs, which it sizes
layout(triangle_strip, max_vertices = 2 * RATE * (RATE - 1)) out;

const int kRate = RATE;
#include "evaluate.glsl"
#include "corner_inputs.glsl"
layout(push_constant) uniform Push {
  uint first_quad;  // of this draw: the output chunk starts there
} push;

// Table 2 for this stage's quad, from the four corners' Table 1 data: its record and quad info.
uint build_quad_record(out vec3 record[kRecordSize]) {
  const uint info = quad_info[corner_quad[0]];
  CornerData corner[4];
  read_corners(corner);
  build_record(corner, cpatch_index_of(info), record);
  return info;
}

#if STORE_OUTPUT
void main() {
  const int quad = corner_quad[0];
  vec3 record[kRecordSize];
  const uint info = build_quad_record(record);
  for (int j = 0; j < kRate; ++j)
    for (int i = 0; i < kRate; ++i) {
      vec3 position, normal;
      evaluate_sample(record, cpatch_index_of(info) >= 0, forward_sides_of(info), i, j, position, normal);
      const int local = (quad - int(push.first_quad)) * kSamples + j * kRate + i;  // chunk-relative
      STORE3(out_positions, local, position);
      STORE3(out_normals, local, normal);
    }
}
#else
#include "shading.glsl"
out gl_PerVertex { vec4 gl_Position; };

// One grid row, evaluated once and emitted twice (as the lower and the upper row of two strips).
struct Row {
  vec4 clip[kRate];
  vec3 normal[kRate];
};

Row evaluate_row(vec3 record[kRecordSize], uint info, int j) {
  Row row;
  for (int i = 0; i < kRate; ++i) {
    vec3 position, normal;
    evaluate_sample(record, cpatch_index_of(info) >= 0, forward_sides_of(info), i, j, position, normal);
    row.clip[i] = clip_position(position);
    row.normal[i] = to_view(normal);
  }
  return row;
}

void emit(Row row, int i) {
  gl_Position = row.clip[i];
  view_normal = row.normal[i];
  EmitVertex();
}

void main() {
  vec3 record[kRecordSize];
  const uint info = build_quad_record(record);
  Row lower = evaluate_row(record, info, 0);
  for (int j = 0; j + 1 < kRate; ++j) {
    const Row upper = evaluate_row(record, info, j + 1);
    for (int i = 0; i < kRate; ++i) {
      emit(upper, i);
      emit(lower, i);
    }
    EndPrimitive();
    lower = upper;
  }
}
#endif
