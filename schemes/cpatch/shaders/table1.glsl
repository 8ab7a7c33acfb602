// Table 1 of Ni et al. 2008 at one vertex p* of valence n, relative to p*, performing the
// floating-point operations of CpatchConverter::convert_vertex (conversion.cpp) in the same
// order, every result `precise` (no fused multiply-add): the points come out bit-identical to
// the CPU's VertexPoints, whichever stage computes them. Needs buffers.glsl with
// BINDING_CONTROL_POINTS, _FIRST_SLOT, _RING, _VALENCE_CONSTANTS and _TRIG, and record.glsl.

// 1/9 in float (1.0f / 9.0f in C++): glslang folds the quotient in double and rounds once,
// which gives the same float.
const float kNinth = 1.0 / 9.0;

vec3 control_point(int vertex) { return LOAD3(control_points, vertex); }

// Ring point k (0: p_{2j}, 1: p_{2j+1}) of slot `slot`, relative to `center`.
vec3 ring_offset(int slot, int k, vec3 center) {
  precise vec3 d = control_point(ring[2 * slot + k]) - center;
  return d;
}

// The Catmull-Clark limit point v - p*: (4 sum p_{2j} + sum p_{2j+1}) / (n (n + 5)), relative.
vec3 limit_offset(int first, int n, vec3 center) {
  precise vec3 sum_direct = vec3(0.0);
  precise vec3 sum_diagonal = vec3(0.0);
  for (int j = 0; j < n; ++j) {
    precise vec3 direct = ring_offset(first + j, 0, center);
    precise vec3 diagonal = ring_offset(first + j, 1, center);
    sum_direct = sum_direct + direct;
    sum_diagonal = sum_diagonal + diagonal;
  }
  precise vec3 v = valence_constants[n].limit_scale * (4.0 * sum_direct + sum_diagonal);
  return v;
}

// f_j - p* = (2 (p_{2j} + p_{2j+2}) + p_{2j+1}) / 9 - p* ... relative: (2 (d0 + d2) + d1) / 9.
vec3 face_offset(int first, int n, int j, vec3 center) {
  precise vec3 d0 = ring_offset(first + j, 0, center);
  precise vec3 d1 = ring_offset(first + j, 1, center);
  precise vec3 d2 = ring_offset(first + (j + 1 < n ? j + 1 : 0), 0, center);
  precise vec3 f = kNinth * (2.0 * (d0 + d2) + d1);
  return f;
}

// e_j = (f_j + f_{j-1}) / 2 (README.md, correction 1).
vec3 edge_offset(vec3 f, vec3 f_previous) {
  precise vec3 e = 0.5 * (f + f_previous);
  return e;
}

vec2 trig_at(int offset, int j) { return vec2(trig[2 * (offset + j)], trig[2 * (offset + j) + 1]); }

// The harmonic sums of the tangent projection, A = sum cos_l (e_l - v), B = sum sin_l (e_l - v).
struct TangentSums {
  vec3 a, b;
};

void add_to_tangent_sums(inout TangentSums s, vec3 e, vec3 v, vec2 cs) {
  precise vec3 d = e - v;
  precise vec3 a = s.a + cs.x * d;
  precise vec3 b = s.b + cs.y * d;
  s.a = a;
  s.b = b;
}

// t_j = v + 1/(n sigma_n) (cos_j A + sin_j B).
vec3 tangent_offset(vec3 v, TangentSums s, float scale, vec2 cs) {
  precise vec3 t = v + scale * (cs.x * s.a + cs.y * s.b);
  return t;
}

// Table 1 at the corner's vertex (record.glsl's CornerData), keeping the sector slot's and the previous edge slot's points.
CornerData corner_data(QuadCorner corner) {
  const int first = first_slot[corner.vertex];
  const int n = first_slot[corner.vertex + 1] - first;
  const int sector = corner.sector_slot - first, previous = corner.prev_edge_slot - first;
  CornerData c;
  c.p = control_point(corner.vertex);
  c.v = limit_offset(first, n, c.p);
  const ValenceConstants k = valence_constants[n];
  TangentSums sums = TangentSums(vec3(0.0), vec3(0.0));
  vec3 f_previous = face_offset(first, n, n - 1, c.p);
  for (int l = 0; l < n; ++l) {
    const vec3 f = face_offset(first, n, l, c.p);
    const vec3 e = edge_offset(f, f_previous);
    if (l == sector) c.f = f, c.e0 = e;
    if (l == previous) c.e1 = e;
    if (n != 4) add_to_tangent_sums(sums, e, c.v, trig_at(k.trig_offset, l));
    f_previous = f;
  }
  // Equation (1): for n = 4 the projection leaves t_j = e_j, taken as it is.
  c.t0 = n == 4 ? c.e0 : tangent_offset(c.v, sums, k.tangent_scale, trig_at(k.trig_offset, sector));
  c.t1 = n == 4 ? c.e1 : tangent_offset(c.v, sums, k.tangent_scale, trig_at(k.trig_offset, previous));
  return c;
}
