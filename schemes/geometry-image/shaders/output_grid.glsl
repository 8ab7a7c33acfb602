// Output passes (E, T, fused E+T): an invocation computes block t, vertices 8 t .. 8 t + 7 of its
// chunk (row-major over the chunk's rows of the n x n grid; output_block), and stores their 24
// floats as six vec4 elements into the chunk's storage-buffer range (STORE_EIGHT). Each pass is two
// dispatches where n >= 8: every block, then the blocks holding a row's end again (kRowEnds).
// Chunks hold whole groups of eight rows (vulkan_subdivider.cpp plans them with gpu::plan_chunks);
// the grid's last block may run past its end, and writes up to seven copies of the last vertex
// into the padding after the outputs.
#extension GL_EXT_control_flow_attributes : require
#include "sdb/dispatch.glsl"

// Padded index of image sample (x, y) (padded (x + 1, y + 1)).
uint padded_index(uint x, uint y) { return (y + 1u) * pc.src_side + (x + 1u); }

uint chunk_vertices() { return pc.rows * pc.dst_side; }

// Padded source index of the chunk's vertex j, clamped to the chunk's last vertex.
uint vertex_source(uint j) {
  const uint v = min(j, chunk_vertices() - 1u);
  return padded_index(v % pc.dst_side, pc.first_row + v / pc.dst_side);
}

// Vertices 8 t .. 8 t + 7 (vec3 v[8]), 96 bytes, as vec4 elements 6 t .. 6 t + 5 of a storage
// buffer of vec4. A macro: GLSL passes no buffer to a function. Floats, not 64-bit words: lavapipe
// stores lane by lane and word by word, and on 64-bit words its code spills a whole 512-bit
// register to the stack per word and reloads one lane from it (harness/gpu/README.md, "Memory
// access on lavapipe").
vec4 floats_of_eight(vec3 v[8], int m) {
  float f[4];
  [[unroll]] for (int q = 0; q < 4; ++q) f[q] = v[(4 * m + q) / 3][(4 * m + q) % 3];
  return vec4(f[0], f[1], f[2], f[3]);
}
#define STORE_EIGHT(out_array, t, v)                                        \
  {                                                                         \
    [[unroll]] for (int m_ = 0; m_ < 6; ++m_)                               \
      out_array[6u * (t) + uint(m_)] = floats_of_eight(v, m_);              \
  }

// A vertex's 3 x 3 source samples: s[3 r + q] at padded index c + (r - 1) S + (q - 1).
void neighbourhood(uint c, out vec3 s[9]) {
  [[unroll]] for (int r = 0; r < 3; ++r)
    [[unroll]] for (int q = 0; q < 3; ++q) s[3 * r + q] = src(c + uint(r) * pc.src_side + uint(q) - pc.src_side - 1u);
}

// How an invocation's eight vertices get their 3 x 3 neighbourhoods (the host picks, per pipeline):
// - kPerVertex: nine fetches each (grids with n < 8);
// - kRowWindow: the block's vertices in one row, one window of 3 rows x 10 columns from the
//   first's (30 fetches where eight apart take 72), each vertex's nine at fixed places in it. Wrong
//   for a block holding a row's end, which the row-end pass then writes again;
// - kCrossingWindow: the row-end pass (kRowEnds): invocation r takes the block holding the chunk's
//   row r's last vertex. Vertex d after the first lies d + 2 texels on in the padded image past a
//   row's end (padded rows are n + 2 long), and with n >= 8 eight vertices cross at most one row's
//   end: a window of 3 x 12, each vertex's nine selected by whether it lies past the row's end,
//   and past the chunk's end copies of its last vertex (the outputs' padding).
// Until 2026-12-06 every block took the crossing window: its selects (216 a block) and the arrays
// they fill cost E and T about a quarter of their time on lavapipe (README.md, "Vulkan passes").
const int kPerVertex = 0, kCrossingWindow = 1, kRowWindow = 2;
layout(constant_id = 1) const int kWindow = kPerVertex;
layout(constant_id = 2) const bool kRowEnds = false;

// The block t (vertices 8 t .. 8 t + 7 of the chunk) this invocation computes; false: none.
bool output_block(out uint t) {
  const uint i = SDB_LINEAR_INVOCATION();
  if (kRowEnds) {
    t = ((i + 1u) * pc.dst_side - 1u) / 8u;
    return i < pc.rows;
  }
  t = i;
  return 8u * t < chunk_vertices();
}

// The neighbourhoods of vertices 8 t .. 8 t + 7 (8 t within the chunk).
void eight_neighbourhoods(uint t, out vec3 s[8][9]) {
  if (kWindow == kPerVertex) {
    [[unroll]] for (int k = 0; k < 8; ++k) neighbourhood(vertex_source(8u * t + uint(k)), s[k]);
    return;
  }
  const uint count = chunk_vertices();
  const uint v0 = 8u * t, x0 = v0 % pc.dst_side;
  const uint first = padded_index(x0, pc.first_row + v0 / pc.dst_side) - pc.src_side - 1u;
  const uint last = pc.src_side * pc.src_side - 1u;  // the window of the grid's last block runs past it
  if (kWindow == kRowWindow) {
    vec3 w[30];  // w[10 r + q] at first + r S + q
    [[unroll]] for (int r = 0; r < 3; ++r)
      [[unroll]] for (int q = 0; q < 10; ++q) w[10 * r + q] = src(min(first + uint(r) * pc.src_side + uint(q), last));
    [[unroll]] for (int k = 0; k < 8; ++k)
      [[unroll]] for (int r = 0; r < 3; ++r)
        [[unroll]] for (int q = 0; q < 3; ++q) s[k][3 * r + q] = w[10 * r + k + q];
    return;
  }
  vec3 w[36];  // w[12 r + q] at first + r S + q
  [[unroll]] for (int r = 0; r < 3; ++r)
    [[unroll]] for (int q = 0; q < 12; ++q) w[12 * r + q] = src(min(first + uint(r) * pc.src_side + uint(q), last));
  [[unroll]] for (int k = 0; k < 8; ++k) {
    const bool crossed = x0 + uint(k) >= pc.dst_side;
    [[unroll]] for (int r = 0; r < 3; ++r)
      [[unroll]] for (int q = 0; q < 3; ++q) s[k][3 * r + q] = crossed ? w[12 * r + k + 2 + q] : w[12 * r + k + q];
  }
  [[unroll]] for (int k = 1; k < 8; ++k)
    if (v0 + uint(k) >= count) s[k] = s[k - 1];
}

// E: 1/36 [1 4 1; 4 16 4; 1 4 1]. The constant is 1.0f / 36.0f as C++ rounds it, given by its
// bits so that no compiler rounds it differently.
vec3 limit_of(vec3 s[9]) {
  precise vec3 edges = (s[3] + s[5]) + (s[1] + s[7]);
  precise vec3 corners = (s[0] + s[8]) + (s[2] + s[6]);
  precise vec3 p = ((16.0 * s[4] + 4.0 * edges) + corners) * uintBitsToFloat(0x3ce38e39u);
  return p;
}

// -0 -> +0, as the CPU's + 0.0f does: a zero tangent component is +0 on both sides of the cut
// (x - x), its products may be -0 on one side only. On the bits, because Vulkan does not promise
// to keep the sign of a zero, and compilers drop a float + 0.0 (lavapipe's LLVM does).
vec3 positive_zero(vec3 v) {
  uvec3 bits = floatBitsToUint(v);
  return uintBitsToFloat(mix(bits, uvec3(0u), equal(bits, uvec3(0x80000000u))));
}

// unit(T_s x T_t), the masks' 1/6 left out. A half turn negates each difference and swaps the two
// outer ones, so the tangents come out exactly negated across the cut and the normal identical.
vec3 normal_of(vec3 s[9]) {
  precise vec3 ts = 4.0 * (s[5] - s[3]) + ((s[2] - s[0]) + (s[8] - s[6]));
  precise vec3 tt = 4.0 * (s[7] - s[1]) + ((s[6] - s[0]) + (s[8] - s[2]));
  precise float cx = ts.y * tt.z - ts.z * tt.y;
  precise float cy = ts.z * tt.x - ts.x * tt.z;
  precise float cz = ts.x * tt.y - ts.y * tt.x;
  // + FLT_MIN keeps the zero cross product of the cut vertices (overwritten by cut_normal.comp)
  // finite, as on the CPU.
  precise float len2 = ((cx * cx + cy * cy) + cz * cz) + uintBitsToFloat(0x00800000u);
  precise float inv = 1.0 / sqrt(len2);
  precise vec3 n = vec3(cx, cy, cz) * inv;
  return positive_zero(n);
}
