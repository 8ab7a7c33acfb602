#version 450
// The limit normals of a shape whose one block is one polynomial (tables.h, patch_*: bicubic for
// Catmull-Clark, quartic box spline for Loop): kernel.cpp's patch_tangents, operation for
// operation, so the normals are the CPU's bits. Its coefficients are summed from the net once per
// invocation (a fragment and a chunk of the block's rows), then each row's derivative cubics, then
// per vertex Horner's rule: a few dozen operations where the net's tangent weights (limit.comp)
// read 2 x 16 weights and 15 points a vertex. kKind: 1 for the triangle.
#extension GL_EXT_control_flow_attributes : require
#include "fragments.glsl"

const bool kTriangle = kKind == 1u;
const uint kMonomials = kTriangle ? 15u : 16u;  // a-major, b ascending (tables.h)
const uint kMaxA = kTriangle ? 4u : 3u;

// The coefficients of u^0 .. u^3 of row v's two derivatives (kernel.cpp's row_coefficients).
void row_coefficients(vec3 c[16], float v, out vec3 du[4], out vec3 dv[4]) {
  precise float v2 = v * v;
  precise float v3 = v2 * v;
  precise float v4 = v3 * v;
  const float vp[5] = float[5](1.0, v, v2, v3, v4);
  uint k = 0u;
  [[unroll]] for (uint a = 0u; a <= kMaxA; ++a) {
    precise vec3 su = vec3(0.0), sv = vec3(0.0);
    [[unroll]] for (uint b = 0u; b <= (kTriangle ? 4u - a : 3u); ++b, ++k) {
      if (a > 0u) {
        precise float w = float(a) * vp[b];
        su = su + c[k] * w;
      }
      if (b > 0u) {
        precise float w = float(b) * vp[b - 1u];
        sv = sv + c[k] * w;
      }
    }
    if (a > 0u) du[a - 1u] = su;
    if (a < 4u) dv[a] = sv;
  }
  if (!kTriangle) du[3] = vec3(0.0);
}

precise vec3 unit_normal(vec3 a, vec3 b) {
  precise vec3 c = vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
  precise float len2 = c.x * c.x + c.y * c.y + c.z * c.z;
  precise float k = len2 > 0.0 ? 1.0 / sqrt(len2) : 0.0;
  precise vec3 n = c * k;
  return n;
}

void main() {
  if (!begin_invocation()) return;
  const uint lh = limit_header();
  // s = 0: this invocation's shape has no patch (a batch joined across shapes may hold both
  // kinds); it loops over nothing.
  const uint s = table_word(lh + kPatchSegments), n = s == 0u ? 0u : table_word(lh + kNetSize);
  const uvec2 rows = chunk_of(s == 0u ? 0u : s + 1u);
  const uint weights = table_word(lh + kPatchWeights), params = table_word(lh + kPatchParams);
  const uint first = 3u * (fragment_word(3u * g_fragment + 1u) - pc.wave_first_vertex) + pc.out_shift;
  // Each coefficient's terms from 0 in the order of the net's slots (slot 0 is the origin).
  precise vec3 c[16];
  [[unroll]] for (uint k = 0u; k < 16u; ++k) c[k] = vec3(0.0);
  for (uint slot = 1u; slot < n; ++slot) {
    const vec3 p = load_net(slot);
    [[unroll]] for (uint k = 0u; k < kMonomials; ++k) c[k] = c[k] + p * number(weights + k * n + slot);
  }
  for (uint j = rows.x; j < rows.y; ++j) {
    vec3 du[4], dv[4];
    row_coefficients(c, number(params + j), du, dv);
    // The block's entries row by row (tables.h): row j starts after j rows of s + 1 (Loop: s + 1 - j') vertices.
    const uint row_start = kTriangle ? j * (s + 1u) - j * (j - 1u) / 2u : j * (s + 1u);
    const uint points = kTriangle ? s + 1u - j : s + 1u;
    for (uint i = 0u; i < points; ++i) {
      const float u = number(params + i);
      precise vec3 a = ((du[3] * u + du[2]) * u + du[1]) * u + du[0];
      precise vec3 b = ((dv[3] * u + dv[2]) * u + dv[1]) * u + dv[0];
      const vec3 nrm = unit_normal(a, b);
      const uint o = first + 3u * (row_start + i);
      imageStore(out_normal, int(o), vec4(nrm.x));
      imageStore(out_normal, int(o + 1u), vec4(nrm.y));
      imageStore(out_normal, int(o + 2u), vec4(nrm.z));
    }
  }
}
