#include "schemes/cpatch/conversion.h"

namespace sdb::cpatch {

void VertexPoints::resize(const CpatchTopology& t) {
  limit.assign(t.num_vertices, {});
  limit_absolute.assign(t.num_vertices, {});
  face.assign(t.num_slots(), {});
  edge.assign(t.num_slots(), {});
  tangent.assign(t.num_slots(), {});
}

void project_tangents(Vec3f v, const Vec3f* e, int n, const ValenceConstants& k, const float* cos_j, const float* sin_j,
                      Vec3f* t) {
  Vec3f a{}, b{};
  for (int l = 0; l < n; ++l) {
    const Vec3f d = e[l] - v;
    a += cos_j[l] * d;
    b += sin_j[l] * d;
  }
  for (int j = 0; j < n; ++j) t[j] = v + k.tangent_scale * (cos_j[j] * a + sin_j[j] * b);
}

// Table 1, relative to p* (see VertexPoints).
void CpatchConverter::convert_vertex(const Vec3f* positions, int vertex, VertexPoints& out) const {
  const int n = t_.valence[vertex];
  if (n == 0) return;  // unused vertex
  const int first = t_.first_slot[vertex];
  const int* ring = &t_.ring[2 * first];
  const Vec3f center = positions[vertex];
  Vec3f* f = &out.face[first];
  Vec3f* e = &out.edge[first];
  Vec3f sum_direct{}, sum_diagonal{};
  // p_{2j+2} is the next sector's p_{2j}: carry it instead of wrapping indices (no modulo).
  const Vec3f first_direct = positions[ring[0]] - center;
  Vec3f d0 = first_direct;
  for (int j = 0; j < n; ++j) {
    const Vec3f d1 = positions[ring[2 * j + 1]] - center;
    const Vec3f d2 = j + 1 < n ? positions[ring[2 * j + 2]] - center : first_direct;
    // f_j = (4 p* + 2 p_{2j} + 2 p_{2j+2} + p_{2j+1}) / 9
    f[j] = (1.0f / 9.0f) * (2.0f * (d0 + d2) + d1);
    sum_direct += d0;
    sum_diagonal += d1;
    d0 = d2;
  }
  // Catmull-Clark limit point: (n^2 p* + 4 sum p_{2j} + sum p_{2j+1}) / (n (n + 5)).
  const ValenceConstants& k = t_.valence_constants[n];
  const Vec3f v = k.limit_scale * (4.0f * sum_direct + sum_diagonal);
  out.limit[vertex] = v;
  out.limit_absolute[vertex] = center + v;
  // e_j = (f_j + f_{j-1}) / 2: the B-spline-to-Bezier edge rule (see README.md, "Corrections").
  e[0] = 0.5f * (f[0] + f[n - 1]);
  for (int j = 1; j < n; ++j) e[j] = 0.5f * (f[j] + f[j - 1]);
  Vec3f* t = &out.tangent[first];
  if (n == 4) {
    // Equation (1): for n = 4 the projection leaves t_j = e_j; taking e_j as it is keeps ordinary
    // patches exactly the B-spline's Bezier form instead of a rounding away from it.
    for (int j = 0; j < 4; ++j) t[j] = e[j];
  } else {
    project_tangents(v, e, n, k, &t_.trig_cos[k.trig_offset], &t_.trig_sin[k.trig_offset], t);
  }
}

void CpatchConverter::convert_vertices(const Vec3f* positions, int begin, int end, VertexPoints& out) const {
  for (int vertex = begin; vertex < end; ++vertex) convert_vertex(positions, vertex, out);
}

// The corner entries every record starts with: p*_i and v, t_0, t_1 relative to it.
void CpatchConverter::write_corners(const Vec3f* positions, const VertexPoints& points, int quad, Vec3f* record) const {
  for (int i = 0; i < 4; ++i) {
    const QuadCorner& c = t_.corners[4 * quad + i];
    record[record_index(i, kP)] = positions[c.vertex];
    record[record_index(i, kV)] = points.limit[c.vertex];
    record[record_index(i, kT0)] = points.tangent[c.sector_slot];
    record[record_index(i, kT1)] = points.tangent[c.prev_edge_slot];
  }
}

void CpatchConverter::build_bicubic(const Vec3f* positions, const VertexPoints& points, int quad, Vec3f* record) const {
  write_corners(positions, points, quad, record);
  const Vec3f origin = record[record_index(0, kP)];
  for (int i = 0; i < 4; ++i) {
    const QuadCorner& c = t_.corners[4 * quad + i];
    record[record_index(i, kF)] = points.face[c.sector_slot] + (record[record_index(i, kP)] - origin);
    record[record_index(i, kX1)] = record[record_index(i, kX2)] = Vec3f{};
  }
}

CpatchInterior cpatch_interior(const CpatchCornerInput c[4], const CpatchCornerWeights w[4]) {
  CpatchInterior out;
  for (int i = 0; i < 4; ++i) {
    const CpatchCornerInput& a = c[i];
    const CpatchCornerInput& b = c[(i + 1) % 4];
    const Vec3f b310 = 0.25f * (a.v + 3.0f * a.t0);
    const Vec3f b130 = 0.25f * (b.v + 3.0f * b.t1);
    out.b211[i] = b310 + w[i].a_i * (b.t1 - a.t0) + w[i].b_next * (a.t0 - a.v) + w[i].k * (a.f - a.e0);
    out.b121[i] = b130 + w[i].a_next * (a.t0 - b.t1) + w[i].b_i * (b.t1 - b.v) + w[i].k * (b.f - b.e1);
  }
  // g* = g(1/2, 1/2) of the bicubic patch the quad would get if it were ordinary.
  Vec3f g_sum{};
  for (int i = 0; i < 4; ++i) g_sum += c[i].v + 3.0f * (c[i].e0 + c[i].e1) + 9.0f * c[i].f;
  const Vec3f g_center = (1.0f / 64.0f) * g_sum;
  const Vec3f* B = out.b211;
  const Vec3f* C = out.b121;
  for (int i = 0; i < 4; ++i) {
    const int i1 = (i + 1) % 4, i2 = (i + 2) % 4, i3 = (i + 3) % 4;
    const Vec3f near = B[i] + C[i] - C[i1] - B[i3];
    const Vec3f far = B[i1] + C[i3] - B[i2] - C[i2];
    out.b112[i] = g_center + (1.0f / 16.0f) * (3.0f * near + far);
  }
  return out;
}

void CpatchConverter::build_cpatch(const Vec3f* positions, const VertexPoints& points, int index, Vec3f* record) const {
  const int quad = t_.extraordinary_quads[index];
  write_corners(positions, points, quad, record);
  // Table 2 in the patch frame: every corner's points shifted from p*_i to p*_0.
  const Vec3f origin = record[record_index(0, kP)];
  CpatchCornerInput in[4];
  for (int i = 0; i < 4; ++i) {
    const QuadCorner& c = t_.corners[4 * quad + i];
    const Vec3f shift = record[record_index(i, kP)] - origin;
    in[i] = {points.limit[c.vertex] + shift,           points.tangent[c.sector_slot] + shift,
             points.tangent[c.prev_edge_slot] + shift, points.face[c.sector_slot] + shift,
             points.edge[c.sector_slot] + shift,       points.edge[c.prev_edge_slot] + shift};
  }
  const CpatchInterior b = cpatch_interior(in, &t_.cpatch_weights[4 * index]);
  for (int i = 0; i < 4; ++i) {
    record[record_index(i, kB211)] = b.b211[i];
    record[record_index(i, kB121)] = b.b121[i];
    record[record_index(i, kB112)] = b.b112[i];
  }
}

void CpatchConverter::build_patch(const Vec3f* positions, const VertexPoints& points, int quad, Vec3f* record) const {
  if (t_.extraordinary[quad])
    build_cpatch(positions, points, t_.extraordinary_index[quad], record);
  else
    build_bicubic(positions, points, quad, record);
}

}  // namespace sdb::cpatch
