#version 450
// cpatch-2pass, pass 1a: Table 1 per vertex (README.md, "Data layout"), one invocation per
// vertex, writing conversion.h's VertexPoints: v - p* per vertex, f - p*, e - p*, t - p* per slot.
#extension GL_GOOGLE_include_directive : require
#include "sdb/dispatch.glsl"

#define BINDING_CONTROL_POINTS 0
#define BINDING_FIRST_SLOT 1
#define BINDING_RING 2
#define BINDING_VALENCE_CONSTANTS 3
#define BINDING_TRIG 4
#define BINDING_LIMIT 5  // and 6, 7, 8: face, edge, tangent points
#define VERTEX_POINTS_WRITTEN
#include "buffers.glsl"
#include "record.glsl"
#include "table1.glsl"

layout(local_size_x = 64) in;
layout(push_constant) uniform Push { uint num_vertices; } push;

void main() {
  const uint vertex = SDB_LINEAR_INVOCATION();
  if (vertex >= push.num_vertices) return;
  const int first = first_slot[vertex];
  const int n = first_slot[vertex + 1] - first;
  if (n == 0) return;  // a vertex no quad uses
  const vec3 center = control_point(int(vertex));
  const vec3 v = limit_offset(first, n, center);
  STORE3(limit_points, vertex, v);
  const ValenceConstants k = valence_constants[n];
  TangentSums sums = TangentSums(vec3(0.0), vec3(0.0));
  vec3 f_previous = face_offset(first, n, n - 1, center);
  for (int l = 0; l < n; ++l) {
    const vec3 f = face_offset(first, n, l, center);
    const vec3 e = edge_offset(f, f_previous);
    STORE3(face_points, first + l, f);
    STORE3(edge_points, first + l, e);
    if (n == 4) STORE3(tangent_points, first + l, e);  // equation (1): t_j = e_j
    if (n != 4) add_to_tangent_sums(sums, e, v, trig_at(k.trig_offset, l));
    f_previous = f;
  }
  if (n == 4) return;
  for (int l = 0; l < n; ++l) STORE3(tangent_points, first + l, tangent_offset(v, sums, k.tangent_scale, trig_at(k.trig_offset, l)));
}
