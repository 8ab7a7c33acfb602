#extension GL_EXT_control_flow_attributes : require  // [[unroll]]: no arrays indexed at run time

// The c-patch buffers, declared once. A shader defines BINDING_<NAME> for each buffer it uses
// (its index in the pipeline's binding list, vulkan_pipelines.cpp) before including this file.
// Layouts mirror the C++ structs of topology.h and conversion.h (README.md, "Data layout"); vec3
// arrays are float arrays (std430 would pad vec3 to 16 bytes).

// Control points, float3 per vertex (per frame).
#ifdef BINDING_CONTROL_POINTS
layout(std430, binding = BINDING_CONTROL_POINTS) restrict readonly buffer ControlPoints { float control_points[]; };
#endif

// Vertex neighbourhoods: slots [first_slot[v], first_slot[v + 1]) of vertex v; ring holds
// p_{2j}, p_{2j+1} of slot j.
#ifdef BINDING_FIRST_SLOT
layout(std430, binding = BINDING_FIRST_SLOT) restrict readonly buffer FirstSlot { int first_slot[]; };
#endif
#ifdef BINDING_RING
layout(std430, binding = BINDING_RING) restrict readonly buffer Ring { int ring[]; };
#endif

// topology.h ValenceConstants, indexed by valence.
struct ValenceConstants {
  float cos_n, sin_n, sigma, tangent_scale, limit_scale;
  int trig_offset;
};
#ifdef BINDING_VALENCE_CONSTANTS
layout(std430, binding = BINDING_VALENCE_CONSTANTS) restrict readonly buffer Valences { ValenceConstants valence_constants[]; };
#endif
// cos and sin of 2 pi j / n at trig[2 (offset + j)] and trig[2 (offset + j) + 1].
#ifdef BINDING_TRIG
layout(std430, binding = BINDING_TRIG) restrict readonly buffer Trig { float trig[]; };
#endif

// topology.h QuadCorner, four per quad.
struct QuadCorner {
  int vertex, sector_slot, prev_edge_slot;
};
#ifdef BINDING_CORNERS
layout(std430, binding = BINDING_CORNERS) restrict readonly buffer Corners { QuadCorner corners[]; };
#endif

// Per quad: bits 0-3 forward_sides, bits 4.. the c-patch index + 1 (0: ordinary quad).
#ifdef BINDING_QUAD_INFO
layout(std430, binding = BINDING_QUAD_INFO) restrict readonly buffer QuadInfo { uint quad_info[]; };
#endif

// topology.h CpatchCornerWeights, four per c-patch.
struct CornerWeights {
  float a_i, b_next, a_next, b_i, k;
};
#ifdef BINDING_CORNER_WEIGHTS
layout(std430, binding = BINDING_CORNER_WEIGHTS) restrict readonly buffer Weights { CornerWeights corner_weights[]; };
#endif

// The SampleGrid's tables for rate kRate (vulkan_resources.cpp, grid_table()), four weights to a
// vec4: one load brings what four scalar loads would.
#ifdef BINDING_GRID
layout(std430, binding = BINDING_GRID) restrict readonly buffer Grid { vec4 grid[]; };
#endif

// Pass 1a output (conversion.h VertexPoints), float3 each, relative to the vertex's p*.
#ifdef VERTEX_POINTS_WRITTEN
#define VERTEX_POINTS_ACCESS writeonly
#else
#define VERTEX_POINTS_ACCESS readonly
#endif
#ifdef BINDING_LIMIT
layout(std430, binding = BINDING_LIMIT) restrict VERTEX_POINTS_ACCESS buffer Limit { float limit_points[]; };
layout(std430, binding = BINDING_LIMIT + 1) restrict VERTEX_POINTS_ACCESS buffer Face { float face_points[]; };
layout(std430, binding = BINDING_LIMIT + 2) restrict VERTEX_POINTS_ACCESS buffer Edge { float edge_points[]; };
layout(std430, binding = BINDING_LIMIT + 3) restrict VERTEX_POINTS_ACCESS buffer Tangent { float tangent_points[]; };
#endif

// Pass 1b output: conversion.h PatchRecord, 28 entries per quad, each a vec4 (xyz; w unused):
// the evaluation reads a record per output vertex, and one vec4 load is much cheaper than three
// scalar ones (lavapipe: 60 % of the evaluation pass).
#ifdef RECORDS_WRITTEN
#define RECORDS_ACCESS writeonly
#else
#define RECORDS_ACCESS readonly
#endif
#ifdef BINDING_RECORDS
layout(std430, binding = BINDING_RECORDS) restrict RECORDS_ACCESS buffer Records { vec4 records[]; };
#endif

// Evaluate-only output: float3 positions and normals of one chunk (chunk-relative indices).
#ifdef BINDING_OUTPUT
layout(std430, binding = BINDING_OUTPUT) restrict writeonly buffer OutPositions { float out_positions[]; };
layout(std430, binding = BINDING_OUTPUT + 1) restrict writeonly buffer OutNormals { float out_normals[]; };
#endif

// Render mode: the camera (gpu::Camera) and the heat map's scale.
#ifdef BINDING_CAMERA
layout(std140, binding = BINDING_CAMERA) uniform CameraBlock {
  mat4 mvp;
  vec4 view_rows[3];  // the view matrix's first three rows
  vec4 heat_scale;    // x: the value shown at the top of the colour scale
} camera;
#endif

// float3 element `index` of a float array (GLSL cannot pass buffer arrays to functions).
#define LOAD3(array, index) vec3(array[3 * (index)], array[3 * (index) + 1], array[3 * (index) + 2])
#define STORE3(array, index, value)      \
  {                                      \
    const vec3 stored_ = (value);        \
    array[3 * (index)] = stored_.x;      \
    array[3 * (index) + 1] = stored_.y;  \
    array[3 * (index) + 2] = stored_.z;  \
  }
