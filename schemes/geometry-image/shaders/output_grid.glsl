// Output passes (E, T, fused E+T): one invocation per vertex of the opened n x n grid, in chunks
// of whole rows that fit one binding (vulkan_subdivider.cpp plans them with gpu::plan_chunks).
// Outputs are tightly packed float3 (Point3), chunk-relative: vertex (x, pc.first_row + r) is
// element r * n + x of the chunk's binding.

// Float texel views (r32f) of the output chunk, written by imageStore; float3 vertex j is texels
// 3 j .. 3 j + 2.
// A macro: GLSL passes no image to a function.
#define STORE_FLOAT3(out_image, j, v)                     \
  {                                                      \
    const vec3 value_ = (v);                             \
    const int texel_ = int(3u * (j));                    \
    imageStore(out_image, texel_, vec4(value_.x));       \
    imageStore(out_image, texel_ + 1, vec4(value_.y));   \
    imageStore(out_image, texel_ + 2, vec4(value_.z));   \
  }

// Padded index of image sample (x, y) (padded (x + 1, y + 1)).
uint padded_index(uint x, uint y) { return (y + 1u) * pc.src_side + (x + 1u); }

// E: 1/36 [1 4 1; 4 16 4; 1 4 1]. The constant is 1.0f / 36.0f as C++ rounds it, given by its
// bits so that no compiler rounds it differently.
vec3 limit_at(uint c) {
  uint s = pc.src_side;
  precise vec3 edges = (src(c - 1u) + src(c + 1u)) + (src(c - s) + src(c + s));
  precise vec3 corners = (src(c - s - 1u) + src(c + s + 1u)) + (src(c - s + 1u) + src(c + s - 1u));
  precise vec3 p = ((16.0 * src(c) + 4.0 * edges) + corners) * uintBitsToFloat(0x3ce38e39u);
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
vec3 normal_at(uint c) {
  uint s = pc.src_side;
  precise vec3 ts = 4.0 * (src(c + 1u) - src(c - 1u)) +
                    ((src(c - s + 1u) - src(c - s - 1u)) + (src(c + s + 1u) - src(c + s - 1u)));
  precise vec3 tt = 4.0 * (src(c + s) - src(c - s)) +
                    ((src(c + s - 1u) - src(c - s - 1u)) + (src(c + s + 1u) - src(c - s + 1u)));
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
