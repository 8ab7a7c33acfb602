// What the halfedge passes share (vulkan.h): bindings, push constants, the level's halfedge
// accessors and the rules of rules.cpp, operation for operation and `precise`, so that the points
// are the cpu's bit for bit. A level's point is an rgba32f texel (xyz, 0); indices and sharpness
// are r32ui / r32f texels.
#extension GL_GOOGLE_include_directive : require
#include "sdb/dispatch.glsl"

layout(local_size_x_id = 0) in;

layout(binding = 0) uniform samplerBuffer src;                          // level d's points
layout(binding = 1, rgba32f) uniform restrict writeonly imageBuffer dst;  // level d + 1's
layout(binding = 2) uniform samplerBuffer dst_read;                     // the same, read (face points)
layout(binding = 3) uniform usamplerBuffer twin_of;
layout(binding = 4) uniform usamplerBuffer vert_of;
layout(binding = 5) uniform usamplerBuffer edge_of;
layout(binding = 6) uniform usamplerBuffer edge_corner;
layout(binding = 7) uniform usamplerBuffer vertex_corner;
layout(binding = 8) uniform samplerBuffer edge_sharpness_of;          // level d (creased levels only)
layout(binding = 9) uniform samplerBuffer vertex_sharpness_of;
layout(binding = 10) uniform samplerBuffer child_edge_sharpness_of;   // level d + 1 (where it has any)
layout(binding = 11) uniform samplerBuffer child_vertex_sharpness_of;
layout(binding = 12) uniform samplerBuffer weights;  // smooth vertex masks per valence: vertex, ring, 1/n (kTable each)
layout(binding = 13) uniform usamplerBuffer base;    // a mixed base level's next, prev, face, face_first

layout(push_constant) uniform Push {
  uint count;      // invocations that do work
  uint vertices;   // level d's
  uint faces;
  uint edges;
  uint face_size;  // 0: the mixed base level (next, prev, face from `base`)
  uint flags;      // kCreased, kChildSharp
  uint base_next, base_prev, base_face, base_first;  // offsets into `base`
} pc;

const uint kNone = 0xffffffffu;
const uint kCreased = 1u, kChildSharp = 2u;
const uint kTable = 1025u;  // rules.h kMaxValence + 1
const uint kMaxValence = 1024u;

uint twin(uint h) { return texelFetch(twin_of, int(h)).x; }
uint vert(uint h) { return texelFetch(vert_of, int(h)).x; }
uint edge(uint h) { return texelFetch(edge_of, int(h)).x; }
uint next_h(uint h) {
  if (pc.face_size == 4u) return (h & ~3u) | ((h + 1u) & 3u);
  if (pc.face_size == 0u) return texelFetch(base, int(pc.base_next + h)).x;
  const uint i = h % pc.face_size;
  return h - i + (i + 1u == pc.face_size ? 0u : i + 1u);
}
uint prev_h(uint h) {
  if (pc.face_size == 4u) return (h & ~3u) | ((h + 3u) & 3u);
  if (pc.face_size == 0u) return texelFetch(base, int(pc.base_prev + h)).x;
  const uint i = h % pc.face_size;
  return h - i + (i == 0u ? pc.face_size - 1u : i - 1u);
}
uint face_h(uint h) {
  if (pc.face_size == 4u) return h >> 2;
  return pc.face_size == 0u ? texelFetch(base, int(pc.base_face + h)).x : h / pc.face_size;
}
vec3 point(uint v) { return texelFetch(src, int(v)).xyz; }
vec3 new_point(uint v) { return texelFetch(dst_read, int(v)).xyz; }
void store(uint v, vec3 p) { imageStore(dst, int(v), vec4(p, 0.0)); }
bool creased() { return (pc.flags & kCreased) != 0u; }
float parent_edge_sharpness(uint e) { return texelFetch(edge_sharpness_of, int(e)).x; }
float child_edge_sharpness(uint e) { return (pc.flags & kChildSharp) != 0u ? texelFetch(child_edge_sharpness_of, int(e)).x : 0.0; }
float parent_vertex_sharpness(uint v) { return creased() ? texelFetch(vertex_sharpness_of, int(v)).x : 0.0; }
float child_vertex_sharpness(uint v) { return (pc.flags & kChildSharp) != 0u ? texelFetch(child_vertex_sharpness_of, int(v)).x : 0.0; }

// rules.cpp's edge_point: Sdc's edge mask (smooth, crease, or the blend by the sharpness).
precise vec3 edge_point(uint e, bool catmark) {
  const uint h = texelFetch(edge_corner, int(e)).x, t = twin(h);
  const vec3 a = point(vert(h)), b = point(vert(next_h(h)));
  const float sharp = creased() ? parent_edge_sharpness(e) : 0.0;
  precise float vw = catmark ? 0.25 : 0.375, fw = catmark ? 0.25 : 0.125;
  if (sharp > 0.0) {
    const float c0 = child_edge_sharpness(2u * e), c1 = child_edge_sharpness(2u * e + 1u);
    if (c0 > 0.0 && c1 > 0.0) {
      precise vec3 m = (a + b) * 0.5;
      return m;
    }
    precise float cw = 1.0 - sharp;
    vw = sharp * 0.5 + cw * vw;
    fw = fw * cw;
  }
  if (t == kNone) {
    precise vec3 m = (a + b) * 0.5;
    return m;
  }
  const vec3 f0 = catmark ? new_point(pc.vertices + face_h(h)) : point(vert(prev_h(h)));
  const vec3 f1 = catmark ? new_point(pc.vertices + face_h(t)) : point(vert(prev_h(t)));
  precise vec3 p = (a + b) * vw + (f0 + f1) * fw;
  return p;
}

// rules.cpp's walk, vertex_rule, mask_of, vertex_mask and apply.
#include "vertex_rule.glsl"

struct Ring {
  vec3 faces, edges, parent_ends, child_ends;
  uint num_faces;
  int parent_sharp, child_sharp, transitions;
  float transition_sum;
};

void ring_edge(inout Ring r, uint e, uint child, uint other) {
  const vec3 q = point(other);
  r.edges = r.edges + q;
  if (!creased()) return;
  const float ps = parent_edge_sharpness(e), cs = child_edge_sharpness(child);
  if (ps > 0.0) r.parent_ends = r.parent_ends + q, ++r.parent_sharp;
  if (cs > 0.0) r.child_ends = r.child_ends + q, ++r.child_sharp;
  if (ps > 0.0 && cs <= 0.0) r.transition_sum = r.transition_sum + ps, ++r.transitions;
}

Ring walk(uint v, bool catmark) {
  precise Ring r = Ring(vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), 0u, 0, 0, 0, 0.0);
  const uint start = texelFetch(vertex_corner, int(v)).x;
  uint k = start;
  for (uint guard = 0u; guard <= kMaxValence; ++guard) {
    ++r.num_faces;
    if (catmark) r.faces = r.faces + new_point(pc.vertices + face_h(k));
    const uint t = twin(k), e = edge(k);
    ring_edge(r, e, 2u * e + (t == kNone || k > t ? 0u : 1u), vert(next_h(k)));
    const uint q = prev_h(k), tq = twin(q);
    if (tq == kNone) {
      ring_edge(r, edge(q), 2u * edge(q) + 1u, vert(q));
      break;
    }
    k = tq;
    if (k == start) break;
  }
  return r;
}

struct Coefficients {
  float vertex, faces, edges, parent_ends, child_ends;
};

Coefficients mask_of(int rule, bool parent, float centre, float ring, bool catmark) {
  Coefficients k = Coefficients(0.0, 0.0, 0.0, 0.0, 0.0);
  if (rule == kSmoothRule || rule == kDartRule) {
    k.vertex = centre, k.edges = ring, k.faces = catmark ? ring : 0.0;
  } else if (rule == kCreaseRule) {
    k.vertex = 0.75;
    if (parent) k.parent_ends = 0.125;
    else k.child_ends = 0.125;
  } else {
    k.vertex = 1.0;
  }
  return k;
}

Coefficients vertex_mask(Ring r, float pvs, float cvs, float centre, float ring, bool catmark) {
  const int prule = vertex_rule(pvs, r.parent_sharp), crule = vertex_rule(cvs, r.child_sharp);
  const Coefficients parent = mask_of(prule, true, centre, ring, catmark);
  if (prule == kSmoothRule || prule == kDartRule || crule == prule) return parent;
  precise float pw = parent_mask_weight(r.transitions, r.transition_sum, pvs, cvs);
  precise float cw = 1.0 - pw;
  const Coefficients child = mask_of(crule, false, centre, ring, catmark);
  precise Coefficients k;
  k.vertex = pw * parent.vertex + cw * child.vertex;
  k.faces = pw * parent.faces + cw * child.faces;
  k.edges = pw * parent.edges + cw * child.edges;
  k.parent_ends = pw * parent.parent_ends;
  k.child_ends = cw * child.child_ends;
  return k;
}

void vertex_point(uint v, bool catmark) {
  if (texelFetch(vertex_corner, int(v)).x == kNone) {
    store(v, point(v));
    return;
  }
  const Ring r = walk(v, catmark);
  const uint n = min(r.num_faces, kMaxValence);
  const float pvs = creased() ? parent_vertex_sharpness(v) : 0.0;
  const float cvs = creased() ? child_vertex_sharpness(v) : 0.0;
  const Coefficients k = vertex_mask(r, pvs, cvs, texelFetch(weights, int(n)).x, texelFetch(weights, int(kTable + n)).x, catmark);
  const vec3 centre = point(v);
  precise vec3 p = ((r.faces * k.faces + r.edges * k.edges) + (r.parent_ends * k.parent_ends + r.child_ends * k.child_ends)) +
                   centre * k.vertex;
  store(v, p);
}
