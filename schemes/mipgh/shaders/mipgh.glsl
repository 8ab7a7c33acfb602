// What the MiPGH passes share (vulkan.h): the bindings, the push constants and the node fetches.
// A level's node is 16 bytes, (x, y, z, 0): one rgba32f texel fetch reads it and one rgba32f
// imageStore writes it (lavapipe loads and stores lane by lane, per component and per access:
// three r32f fetches and stores cost more; harness/gpu/README.md). The output is packed xyz floats,
// written through r32f image views; the D-LoD's index arrays and every table are r32ui texels.
// The arithmetic is the CPU's (tile.cpp, shader.h), operation for operation and `precise` (no
// fused multiply-adds, no reassociation), so the stencils' nodes equal the CPU's.
#extension GL_GOOGLE_include_directive : require
#include "sdb/dispatch.glsl"

layout(local_size_x_id = 0) in;

layout(binding = 0) uniform samplerBuffer src_nodes;                           // level sigma
layout(binding = 1, rgba32f) uniform restrict writeonly imageBuffer dst_nodes;     // level sigma + 1, or the limit
layout(binding = 2, rgba32f) uniform restrict writeonly imageBuffer normal_nodes;  // the limit's normals
layout(binding = 3) uniform usamplerBuffer lod;       // every level's D-facet index arrays
layout(binding = 4) uniform usamplerBuffer words;     // the tables (vulkan.cpp, Tables)
layout(binding = 5) uniform samplerBuffer weights;    // the mask tables' weights
layout(binding = 6, r32f) uniform restrict writeonly imageBuffer out_position;
layout(binding = 7, r32f) uniform restrict writeonly imageBuffer out_normal;
layout(binding = 8) uniform samplerBuffer normals_in;  // the limit's normals (rgba32f), read by the output pass
// The same level and normal buffers as bindings 1 and 2, written as storage buffers of vec4:
// lavapipe stores lane by lane and component by component, and a vec4 store costs less than an
// rgba32f imageStore and, in time, than two 64-bit words (harness/gpu/README.md). Where a level
// is past the device's storage-buffer range (128 MiB on lavapipe) the texel views write it
// (kVec4 = false).
layout(std430, binding = 9) restrict writeonly buffer DstVec4 { vec4 dst_vec4[]; };
layout(std430, binding = 10) restrict writeonly buffer NormalVec4 { vec4 normal_vec4[]; };
layout(constant_id = 4) const bool kVec4 = true;
// The pipeline writes the limit straight into the output (bindings 6 and 7, packed xyz), not
// into a level's buffers: where the limit is the whole output.
layout(constant_id = 3) const bool kToOutput = false;
// The output's buffers as storage buffers of packed vec3 too (scalar layout, a 12-byte stride;
// kOutVec3, where one binding covers them): one vec3 lane store a vertex, where three r32f
// imageStores made 4% more instructions per execute and a 64-bit word and a float 2% more
// (harness/gpu/README.md).
#extension GL_EXT_scalar_block_layout : require
layout(scalar, binding = 11) restrict writeonly buffer OutPositionVec3 { vec3 out_position_vec3[]; };
layout(scalar, binding = 12) restrict writeonly buffer OutNormalVec3 { vec3 out_normal_vec3[]; };
layout(constant_id = 5) const bool kOutVec3 = true;

layout(push_constant) uniform Push {
  uint count;        // invocations that do work
  uint per_item;     // targets per D-facet or per D-edge
  uint table;        // the pass's table, in words
  uint lod_base;     // level sigma's D-LoD, in words
  uint n;            // nodes along a D-facet's side at level sigma
  uint facet_nodes;  // a D-facet's index array at level sigma
  uint dst_base;     // the first target node: a level's interiors (D-facet passes)
  uint interior;     // nodes per D-facet interior at the target level
  uint rows;         // level sigma's side rows (MeshProcessor::side_row_table), in words
  uint begins;       // a mask table's term ranges, in words
  uint sources;      // and its source nodes
  uint weight_base;  // and its weights, in floats
  uint pick;         // the output pass's node list (0xffffffff: node i is output i)
  uint facet_list;   // D-facets of mixed kinds: the pass's (D-LoD offset, first target) per D-facet; 0: uniform
  uint facet_lod;    // D-facets of mixed kinds: each D-facet's D-LoD offset at level sigma; 0: f * facet_nodes
  uint scatter;      // the output pass's output slots (0: slot i), for an adaptive level's drawn nodes
  vec4 origin;       // the control box's centre (levels are relative to it): added where the output is written
} pc;

uint word(uint i) { return texelFetch(words, int(i)).x; }
vec3 node(uint i) { return texelFetch(src_nodes, int(i)).xyz; }
// Packed xyz floats: the output (r32f views; GLSL passes no image to a function, hence a macro).
#define STORE_XYZ(image, i, v)                 \
  {                                            \
    const int o_ = int(3u * (i));              \
    imageStore(image, o_, vec4((v).x));        \
    imageStore(image, o_ + 1, vec4((v).y));    \
    imageStore(image, o_ + 2, vec4((v).z));    \
  }
#define STORE_OUTPUT_XYZ(image, vec3s, i, v) \
  {                                          \
    if (kOutVec3) vec3s[i] = (v);            \
    else STORE_XYZ(image, i, v)              \
  }
void store_output(uint i, vec3 p, vec3 n) {
  STORE_OUTPUT_XYZ(out_position, out_position_vec3, i, p);
  STORE_OUTPUT_XYZ(out_normal, out_normal_vec3, i, n);
}
// Steps push a zero origin; a limit written straight into the output the box's centre (as the
// cpu adds it: after the node is computed).
void store(uint i, vec3 node) {
  precise vec3 p = node + pc.origin.xyz;
  if (kToOutput) STORE_OUTPUT_XYZ(out_position, out_position_vec3, i, p)
  else if (kVec4) dst_vec4[i] = vec4(p, 0.0);
  else imageStore(dst_nodes, int(i), vec4(p, 0.0));
}
void store_normal(uint i, vec3 n) {
  if (kToOutput) STORE_OUTPUT_XYZ(out_normal, out_normal_vec3, i, n)
  else if (kVec4) normal_vec4[i] = vec4(n, 0.0);
  else imageStore(normal_nodes, int(i), vec4(n, 0.0));
}
// tile.cpp's unit_normals: a zero normal stays zero, without a branch.
vec3 unit(vec3 t1, vec3 t2) {
  precise vec3 c = vec3(t1.y * t2.z - t1.z * t2.y, t1.z * t2.x - t1.x * t2.z, t1.x * t2.y - t1.y * t2.x);
  precise float l2 = c.x * c.x + c.y * c.y + c.z * c.z;
  return c * (1.0 / sqrt(l2 + 1e-37));
}
