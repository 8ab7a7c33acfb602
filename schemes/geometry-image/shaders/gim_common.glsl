// Shared by the geometry-image compute passes (../README.md, "Vulkan passes"): the work layout
// and the push constants.
//
// A padded image of side S is three storage buffers, one per coordinate plane (x, y, z), each
// S * S floats in row-major order, exactly the CPU's planes (masks.h): value(c, col, row) is
// plane c at row * S + col. One binding per plane keeps every binding under the device's
// maxStorageBufferRange for images three times larger than one binding could hold.
//
// Every value the masks compute is `precise` (SPIR-V NoContraction: no fused multiply-add), and
// the sums are written in the CPU's order: opposite stencil samples paired first, pair sums added
// in a fixed order, so that samples the cut identifies come out bit-identical (masks.h).
#extension GL_GOOGLE_include_directive : require

// One invocation per destination sample: a row of work groups per destination row, x along it
// (gl_GlobalInvocationID = (column, row); columns past the row's end return). Work groups of
// local_size_x invocations, set by the host (vulkan_subdivider.cpp, kLocalSize).
layout(local_size_x_id = 0) in;

layout(push_constant) uniform Push {
  uint src_side;   // padded side of the source image
  uint dst_side;   // padded side of the destination image; output passes: n = src_side - 2
  uint first_row;  // output passes: the chunk's first row of the n x n output
  uint rows;       // output passes: the chunk's rows
} pc;

// The column of this invocation in a pass whose formula depends on the column's parity (L):
// the first half of each work group takes the even columns of the group's span, the second half
// the odd ones, so that a SIMD group (a warp, lavapipe's 8 lanes) takes one branch, not both.
// Row parity is uniform already (a row of work groups per row). local_size_x must be even.
uint parity_grouped_column() {
  uint half_size = gl_WorkGroupSize.x / 2u;
  uint lane = gl_LocalInvocationID.x;
  uint odd = lane >= half_size ? 1u : 0u;
  return gl_WorkGroupID.x * gl_WorkGroupSize.x + 2u * (lane - odd * half_size) + odd;
}
