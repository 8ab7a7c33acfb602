#version 450
// Normals at the cut vertices a, b, c, d, where both tangent masks vanish (masks.h): the limit
// tangent plane is spanned by T1 = g(c+u) - g(c+e) and T2 = g(c+u+e) - g(c-u+e), n = unit(T2 x T1).
// One work group per output chunk; its first four invocations write their vertex if the chunk
// holds it.
#include "gim_common.glsl"
#include "source_planes.glsl"

// Per cut vertex: output vertex, then padded offsets of c, c+u, c+e, c+u+e, c-u+e
// (masks.h CutVertexStencil).
layout(std430, binding = 1) readonly buffer Stencils { int stencils[24]; };
layout(std430, binding = 2) writeonly buffer Normals { float normals[]; };

void main() {
  uint i = gl_LocalInvocationIndex;
  if (i >= 4u) return;
  uint vertex = uint(stencils[6u * i]);
  uint first = pc.first_row * pc.dst_side;
  if (vertex < first || vertex - first >= pc.rows * pc.dst_side) return;
  uint u = uint(stencils[6u * i + 2u]), e = uint(stencils[6u * i + 3u]);
  uint ue = uint(stencils[6u * i + 4u]), mu_e = uint(stencils[6u * i + 5u]);
  precise vec3 a = src(ue) - src(mu_e);  // T2
  precise vec3 b = src(u) - src(e);      // T1
  precise float cx = a.y * b.z - a.z * b.y;
  precise float cy = a.z * b.x - a.x * b.z;
  precise float cz = a.x * b.y - a.y * b.x;
  precise float len2 = (cx * cx + cy * cy) + cz * cz;
  precise float inv = len2 > 0.0 ? 1.0 / sqrt(len2) : 0.0;
  precise vec3 n = vec3(cx, cy, cz) * inv;
  uint j = vertex - first;
  normals[3u * j] = n.x;
  normals[3u * j + 1u] = n.y;
  normals[3u * j + 2u] = n.z;
}
