// The four corners of a quad as corner.vert hands them on (geometry and tessellation control
// stages read them as arrays).
layout(location = 0) in vec3 corner_p[];
layout(location = 1) in vec3 corner_v[];
layout(location = 2) in vec3 corner_t0[];
layout(location = 3) in vec3 corner_t1[];
layout(location = 4) in vec3 corner_f[];
layout(location = 5) in vec3 corner_e0[];
layout(location = 6) in vec3 corner_e1[];
layout(location = 7) flat in int corner_quad[];  // the same for all four

void read_corners(out CornerData corner[4]) {
  [[unroll]] for (int i = 0; i < 4; ++i)
    corner[i] = CornerData(corner_p[i], corner_v[i], corner_t0[i], corner_t1[i], corner_f[i], corner_e0[i], corner_e1[i]);
}
