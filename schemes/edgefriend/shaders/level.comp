#version 450
// One Edge-Friend level (rules.cpp): invocation i computes vertex i's vertex point (i < V) and quad
// i's face point and the points of its two owned edges (i < Q), operation for operation and
// `precise`, so that the points are the cpu's bit for bit. Points are rgba32f texels (xyz, 0);
// a quad's corners and its friends are one rgba32ui texel each (the paper's uint4).
#extension GL_GOOGLE_include_directive : require
#include "sdb/dispatch.glsl"

layout(local_size_x_id = 0) in;
layout(binding = 0) uniform samplerBuffer src;                          // level d's points
layout(binding = 1, rgba32f) uniform restrict writeonly imageBuffer dst;  // level d + 1's
layout(binding = 2) uniform usamplerBuffer quads;                       // corners 0..3
layout(binding = 3) uniform usamplerBuffer friends;                     // friend0, sharpness0, friend1, sharpness1
layout(binding = 4) uniform usamplerBuffer vertex_corner;
layout(binding = 5) uniform samplerBuffer vertex_sharpness;  // (flags & kVertexSharp) only
layout(binding = 6) uniform samplerBuffer weights;           // smooth masks per valence: V, E, D (kTable each)
layout(binding = 7) uniform usamplerBuffer out_index;        // (flags & kOutIndex) only

layout(push_constant) uniform Push {
  uint count;  // max(V, Q)
  uint vertices;
  uint quads;
  uint flags;
} pc;

const uint kNone = 0xffffffffu;
const uint kCreased = 1u, kVertexSharp = 2u, kOutIndex = 4u;  // vulkan.cpp
const uint kTable = 1025u;                                    // topology.h kMaxValence + 1
const uint kMaxValence = 1024u;
const float kInfinite = 10.0;

vec3 point(uint v) { return texelFetch(src, int(v)).xyz; }
void store(uint i, vec3 p) {
  const uint j = (pc.flags & kOutIndex) != 0u ? texelFetch(out_index, int(i)).x : i;
  if (j != kNone) imageStore(dst, int(j), vec4(p, 0.0));
}
uint child_of_vertex(uint v) { return v < pc.quads ? 4u * v : 3u * pc.quads + v; }
float decay(float s) { return s >= kInfinite ? s : (s > 1.0 ? s - 1.0 : 0.0); }

#include "vertex_rule.glsl"

struct Ring {
  vec3 edges, diagonals, parent_ends, child_ends;
  uint n;
  int parent_sharp, child_sharp, transitions;
  float transition_sum;
};

// A `for` with a guard and plain accumulators: a `do while` over a `precise` struct summed the
// first edge twice on lavapipe (LLVM 15) at the valence-3 corners of catmark_cube's level 2.
Ring walk(uint start) {
  precise vec3 edges = vec3(0.0), diagonals = vec3(0.0), parent_ends = vec3(0.0), child_ends = vec3(0.0);
  precise float transition_sum = 0.0;
  uint n = 0u;
  int parent_sharp = 0, child_sharp = 0, transitions = 0;
  const bool creased = (pc.flags & kCreased) != 0u;
  uint c = start;
  for (uint guard = 0u; guard <= 4u * pc.quads; ++guard) {
    ++n;
    const uvec4 corners = texelFetch(quads, int(c >> 2));
    const vec3 e = point(corners[(c ^ 3u) & 3u]);
    edges = edges + e;
    diagonals = diagonals + point(corners[(c ^ 2u) & 3u]);
    const uvec4 f = texelFetch(friends, int(c >> 2));
    const bool edge30 = ((c + 1u) & 2u) == 0u;
    const uint fr = edge30 ? f.z : f.x;
    if (creased) {
      const float sharp = uintBitsToFloat(edge30 ? f.w : f.y);
      if (sharp > 0.0) {
        parent_ends = parent_ends + e, ++parent_sharp;
        if (decay(sharp) > 0.0) child_ends = child_ends + e, ++child_sharp;
        else transition_sum = transition_sum + sharp, ++transitions;
      }
    }
    c = 2u * fr + (c & 1u);
    if (c == start) break;
  }
  return Ring(edges, diagonals, parent_ends, child_ends, n, parent_sharp, child_sharp, transitions, transition_sum);
}

struct Coefficients {
  float vertex, edges, diagonals, parent_ends, child_ends;
};

Coefficients mask_of(int rule, bool parent, uint n) {
  Coefficients k = Coefficients(0.0, 0.0, 0.0, 0.0, 0.0);
  if (rule == kSmoothRule || rule == kDartRule) {
    k.vertex = texelFetch(weights, int(n)).x;
    k.edges = texelFetch(weights, int(kTable + n)).x;
    k.diagonals = texelFetch(weights, int(2u * kTable + n)).x;
  } else if (rule == kCreaseRule) {
    k.vertex = 0.75;
    if (parent) k.parent_ends = 0.125;
    else k.child_ends = 0.125;
  } else {
    k.vertex = 1.0;
  }
  return k;
}

Coefficients vertex_mask(Ring r, float pvs) {
  const uint n = min(r.n, kMaxValence);
  const float cvs = decay(pvs);
  const int prule = vertex_rule(pvs, r.parent_sharp), crule = vertex_rule(cvs, r.child_sharp);
  const Coefficients parent = mask_of(prule, true, n);
  if (prule == kSmoothRule || prule == kDartRule || crule == prule) return parent;
  precise float pw = parent_mask_weight(r.transitions, r.transition_sum, pvs, cvs);
  precise float cw = 1.0 - pw;
  const Coefficients child = mask_of(crule, false, n);
  precise Coefficients k;
  k.vertex = pw * parent.vertex + cw * child.vertex;
  k.edges = pw * parent.edges + cw * child.edges;
  k.diagonals = pw * parent.diagonals + cw * child.diagonals;
  k.parent_ends = pw * parent.parent_ends;
  k.child_ends = cw * child.child_ends;
  return k;
}

void vertex_point(uint v) {
  const uint start = texelFetch(vertex_corner, int(v)).x, to = child_of_vertex(v);
  if (start == kNone) {
    store(to, vec3(0.0));
    return;
  }
  const Ring r = walk(start);
  const float vs = (pc.flags & kVertexSharp) != 0u ? texelFetch(vertex_sharpness, int(v)).x : 0.0;
  const Coefficients k = vertex_mask(r, vs);
  const vec3 centre = point(v);
  precise vec3 p = ((r.edges * k.edges + r.diagonals * k.diagonals) + (r.parent_ends * k.parent_ends + r.child_ends * k.child_ends)) +
                   centre * k.vertex;
  store(to, p);
}

precise vec3 edge_point(vec3 a, vec3 b, vec3 near, vec3 far, float sharp) {
  precise float vw = 0.375, ow = 0.0625;
  if (sharp > 0.0) {
    if (decay(sharp) > 0.0) {
      precise vec3 m = (a + b) * 0.5;
      return m;
    }
    precise float cw = 1.0 - sharp;
    vw = sharp * 0.5 + cw * vw;
    ow = ow * cw;
  }
  precise vec3 p = (a + b) * vw + (near + far) * ow;
  return p;
}

void quad_points(uint q) {
  const uvec4 x = texelFetch(quads, int(q));
  const vec3 A = point(x.x), B = point(x.y), C = point(x.z), D = point(x.w);
  const uvec4 f = texelFetch(friends, int(q));
  const uvec4 y0 = texelFetch(quads, int(f.x >> 1)), y1 = texelFetch(quads, int(f.z >> 1));
  // The friend's two corners away from the shared edge: 2 (1 - side) and 2 (1 - side) + 1.
  const uint a0 = 2u * (1u - (f.x & 1u)), a1 = 2u * (1u - (f.z & 1u));
  const bool creased = (pc.flags & kCreased) != 0u;
  const float s0 = creased ? uintBitsToFloat(f.y) : 0.0, s1 = creased ? uintBitsToFloat(f.w) : 0.0;
  precise vec3 face = (((A + B) + C) + D) * 0.25;
  store(4u * q + 1u, face);
  precise vec3 near0 = A + D, far0 = point(y0[a0]) + point(y0[a0 + 1u]);
  store(4u * (f.x >> 1) + 2u + (f.x & 1u), edge_point(B, C, near0, far0, s0));
  precise vec3 near1 = B + C, far1 = point(y1[a1]) + point(y1[a1 + 1u]);
  store(4u * (f.z >> 1) + 2u + (f.z & 1u), edge_point(D, A, near1, far1, s1));
}

void main() {
  const uint i = SDB_LINEAR_INVOCATION();
  if (i >= pc.count) return;
  if (i < pc.vertices) vertex_point(i);
  if (i < pc.quads) quad_points(i);
}
