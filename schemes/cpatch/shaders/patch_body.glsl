// cpatch-tess, tessellation evaluation stage: one invocation per grid sample the tessellator
// generates. gl_TessCoord is (u, v) = (i, j) / (N - 1) up to the tessellator's rounding; the
// sample index (i, j) is recovered by rounding and the patch is evaluated at exactly that grid
// sample with the same weights as every other variant, so positions (borders included) are the
// CPU's bits. In evaluate-only mode the largest |gl_TessCoord (N - 1) - (i, j)| is kept in
// tess_coord_error (atomic max of the float's bits), to check the tessellator really samples the
// uniform grid.
//   STORE_OUTPUT 0 (render mode): clip position and view normal for the rasterizer.
//   STORE_OUTPUT 1 (evaluate-only mode): stores the sample's position and normal; the vertex is
//     placed outside the clip volume, so nothing is rasterized.
#extension GL_GOOGLE_include_directive : require

// Bindings 0-5 are corner.vert's, 7 patch.tesc's.
#define BINDING_QUAD_INFO 6
#define BINDING_GRID 8
#if STORE_OUTPUT
#define BINDING_OUTPUT 9  // and 10
#else
#define BINDING_CAMERA 9
#endif
#include "buffers.glsl"
#include "record.glsl"

layout(constant_id = 0) const int kRate = 2;
#include "evaluate.glsl"
#if STORE_OUTPUT
layout(std430, binding = 11) restrict buffer TessCoordError { uint tess_coord_error; };
#endif

layout(quads, equal_spacing, ccw) in;
layout(push_constant) uniform Push { uint first_quad; } push;

layout(location = 0) in vec3 record_p[];
layout(location = 1) in vec3 record_v[];
layout(location = 2) in vec3 record_t0[];
layout(location = 3) in vec3 record_t1[];
layout(location = 4) in vec3 record_x0[];
layout(location = 5) in vec3 record_x1[];
layout(location = 6) in vec3 record_x2[];
layout(location = 7) patch in int patch_quad;

#if !STORE_OUTPUT
#include "shading.glsl"
#endif

void main() {
  const int quad = patch_quad;
  const uint info = quad_info[quad];
  vec3 record[kRecordSize];
  [[unroll]] for (int k = 0; k < 4; ++k) {
    record[record_index(k, kP)] = record_p[k];
    record[record_index(k, kV)] = record_v[k];
    record[record_index(k, kT0)] = record_t0[k];
    record[record_index(k, kT1)] = record_t1[k];
    record[record_index(k, kX0)] = record_x0[k];
    record[record_index(k, kX1)] = record_x1[k];
    record[record_index(k, kX2)] = record_x2[k];
  }
  const vec2 scaled = gl_TessCoord.xy * float(kRate - 1);
  const ivec2 sample_index = ivec2(round(scaled));
  vec3 position, normal;
  evaluate_sample(record, cpatch_index_of(info) >= 0, forward_sides_of(info), sample_index.x, sample_index.y, position,
                  normal);
#if STORE_OUTPUT
  const int local = (quad - int(push.first_quad)) * kSamples + sample_index.y * kRate + sample_index.x;  // chunk-relative
  STORE3(out_positions, local, position);
  STORE3(out_normals, local, normal);
  const vec2 error = abs(scaled - vec2(sample_index));
  atomicMax(tess_coord_error, floatBitsToUint(max(error.x, error.y)));
  gl_Position = vec4(0.0, 0.0, -1.0, 1.0);  // outside the depth range [0, 1]: clipped
#else
  gl_Position = clip_position(position);
  view_normal = to_view(normal);
#endif
}
