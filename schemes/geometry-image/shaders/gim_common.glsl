// Shared by the geometry-image compute passes (../README.md, "Vulkan passes"): the work layout
// and the push constants.
//
// A padded image of side S is one buffer of S * S vec4 texels in row-major order, (x, y, z, 0)
// per sample, the CPU's three planes (masks.h) interleaved: sample (col, row) is texel
// row * S + col. A texel view may cover maxTexelBufferElements texels (2 GiB of vec4 on lavapipe),
// so an image is not bound by maxStorageBufferRange (128 MiB there).
//
// Every value the masks compute is `precise` (SPIR-V NoContraction: no fused multiply-add), and
// the sums are written in the CPU's order: opposite stencil samples paired first, pair sums added
// in a fixed order, so that samples the cut identifies come out bit-identical (masks.h).
#extension GL_GOOGLE_include_directive : require

// Image passes: one invocation per sample or 2 x 2 block (each pass says which), a row of work
// groups per row of them, x along it (gl_GlobalInvocationID = (column, row); columns past the
// row's end return). Work groups of local_size_x invocations, set by the host
// (vulkan_subdivider.cpp, kLocalSize).
layout(local_size_x_id = 0) in;

layout(push_constant) uniform Push {
  uint src_side;   // padded side of the source image
  uint dst_side;   // padded side of the destination image; output passes: n = src_side - 2
  uint first_row;  // output passes: the chunk's first row of the n x n output
  uint rows;       // output passes: the chunk's rows
} pc;

