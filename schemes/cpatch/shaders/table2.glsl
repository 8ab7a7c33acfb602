// Figure 6 and Table 2 of Ni et al. 2008: a quad's patch record from its four corners' Table 1
// points, with the operations of CpatchConverter::build_bicubic / build_cpatch and
// cpatch_interior (conversion.cpp) in the same order, every result `precise`. Needs record.glsl,
// table1.glsl (CornerData) and buffers.glsl with BINDING_CORNER_WEIGHTS.

struct CpatchCorner {  // conversion.h CpatchCornerInput, in the patch frame (relative to p*_0)
  vec3 v, t0, t1, f, e0, e1;
};

vec3 shifted(vec3 point, vec3 shift) {
  precise vec3 r = point + shift;
  return r;
}

// b211, b121 of corner i (Table 2).
void edge_interior(CpatchCorner a, CpatchCorner b, CornerWeights w, out vec3 b211, out vec3 b121) {
  precise vec3 b310 = 0.25 * (a.v + 3.0 * a.t0);
  precise vec3 b130 = 0.25 * (b.v + 3.0 * b.t1);
  precise vec3 r211 = b310 + w.a_i * (b.t1 - a.t0) + w.b_next * (a.t0 - a.v) + w.k * (a.f - a.e0);
  precise vec3 r121 = b130 + w.a_next * (a.t0 - b.t1) + w.b_i * (b.t1 - b.v) + w.k * (b.f - b.e1);
  b211 = r211;
  b121 = r121;
}

// g* = g(1/2, 1/2) of the bicubic the quad would get if it were ordinary.
vec3 bicubic_center(CpatchCorner c[4]) {
  precise vec3 sum = vec3(0.0);
  [[unroll]] for (int i = 0; i < 4; ++i) {
    precise vec3 term = c[i].v + 3.0 * (c[i].e0 + c[i].e1) + 9.0 * c[i].f;
    sum = sum + term;
  }
  precise vec3 center = (1.0 / 64.0) * sum;
  return center;
}

void cpatch_interior(CornerData corner[4], int cpatch_index, inout vec3 record[kRecordSize]) {
  CpatchCorner c[4];
  [[unroll]] for (int i = 0; i < 4; ++i) {
    precise vec3 shift = corner[i].p - corner[0].p;
    c[i] = CpatchCorner(shifted(corner[i].v, shift), shifted(corner[i].t0, shift), shifted(corner[i].t1, shift),
                        shifted(corner[i].f, shift), shifted(corner[i].e0, shift), shifted(corner[i].e1, shift));
  }
  vec3 B[4], C[4];
  [[unroll]] for (int i = 0; i < 4; ++i) edge_interior(c[i], c[(i + 1) % 4], corner_weights[4 * cpatch_index + i], B[i], C[i]);
  const vec3 g_center = bicubic_center(c);
  [[unroll]] for (int i = 0; i < 4; ++i) {
    const int i1 = (i + 1) % 4, i2 = (i + 2) % 4, i3 = (i + 3) % 4;
    precise vec3 near_terms = B[i] + C[i] - C[i1] - B[i3];
    precise vec3 far_terms = B[i1] + C[i3] - B[i2] - C[i2];
    precise vec3 b112 = g_center + (1.0 / 16.0) * (3.0 * near_terms + far_terms);
    record[record_index(i, kX0)] = B[i];
    record[record_index(i, kX1)] = C[i];
    record[record_index(i, kX2)] = b112;
  }
}

// The record of a quad: corner entries, then f^i (ordinary) or the c-patch interior.
void build_record(CornerData corner[4], int cpatch_index, out vec3 record[kRecordSize]) {
  [[unroll]] for (int i = 0; i < 4; ++i) {
    record[record_index(i, kP)] = corner[i].p;
    record[record_index(i, kV)] = corner[i].v;
    record[record_index(i, kT0)] = corner[i].t0;
    record[record_index(i, kT1)] = corner[i].t1;
  }
  if (cpatch_index < 0) {
    [[unroll]] for (int i = 0; i < 4; ++i) {
      precise vec3 shift = corner[i].p - corner[0].p;
      precise vec3 f = corner[i].f + shift;
      record[record_index(i, kX0)] = f;
      record[record_index(i, kX1)] = vec3(0.0);
      record[record_index(i, kX2)] = vec3(0.0);
    }
  } else {
    cpatch_interior(corner, cpatch_index, record);
  }
}
