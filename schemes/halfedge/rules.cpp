#include "schemes/halfedge/rules.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "harness/refined/float3.h"
#include "harness/refined/vertex_rule.h"

namespace sdb::halfedge {
namespace {

using refined::P3;
using refined::at;
using refined::operator+;
using refined::operator*;
inline void store(Point3* p, uint32_t i, P3 v) { p[i] = {v.x, v.y, v.z}; }

using refined::kCornerRule, refined::kCreaseRule, refined::kDartRule, refined::kSmoothRule, refined::vertex_rule;

// What the vertex rules read of a ring, in one walk: sums of the new face points and of the other
// ends of the edges, and the other ends of the sharp edges before and after the step.
struct Ring {
  P3 faces{0, 0, 0}, edges{0, 0, 0};
  P3 parent_ends{0, 0, 0}, child_ends{0, 0, 0};  // the two crease edges' other ends, summed
  uint32_t num_faces = 0;
  int parent_sharp = 0, child_sharp = 0, transitions = 0;
  float transition_sum = 0;
};

// `catmark`: face points are level c's points [V, V + F) (face_base).
Ring walk(const Step& s, uint32_t v, bool catmark, bool creased) {
  const Level& p = *s.p;
  const uint32_t face_base = p.num_vertices;
  Ring r;
  const uint32_t start = p.vertex_corner[v];
  uint32_t k = start;
  auto edge = [&](uint32_t e, uint32_t child, uint32_t other) {
    const P3 q = at(s.src, other);
    r.edges = r.edges + q;
    if (!creased) return;
    const float ps = p.edge_sharpness[e], cs = s.c->edge_sharpness.empty() ? 0.0f : s.c->edge_sharpness[child];
    if (ps > 0.0f) r.parent_ends = r.parent_ends + q, ++r.parent_sharp;
    if (cs > 0.0f) r.child_ends = r.child_ends + q, ++r.child_sharp;
    if (ps > 0.0f && cs <= 0.0f) r.transition_sum += ps, ++r.transitions;
  };
  while (true) {
    ++r.num_faces;
    if (catmark) r.faces = r.faces + at(s.dst, face_base + p.face(k));
    const uint32_t t = p.twin[k], e = p.edge[k];
    edge(e, 2 * e + (t == kNone || k > t ? 0 : 1), p.vert[p.next(k)]);
    const uint32_t q = p.prev(k), tq = p.twin[q];
    if (tq == kNone) {  // the trailing boundary edge: its half at v is 2e + 1 (topology.h)
      edge(p.edge[q], 2 * p.edge[q] + 1, p.vert[q]);
      break;
    }
    if ((k = tq) == start) break;
  }
  return r;
}

// The vertex point: Sdc::Scheme::ComputeVertexVertexMask's coefficients (refined::vertex_point_mask)
// on the ring's sums, in the shader's order.
P3 apply(const refined::RuleMask& k, const Ring& r, P3 centre) {
  return ((r.faces * k.faces + r.edges * k.edges) + (r.parent_ends * k.parent_ends + r.child_ends * k.child_ends)) +
         centre * k.vertex;
}

void vertex_points(const Step& s, uint32_t first, uint32_t last, bool catmark) {
  const Level& p = *s.p;
  for (uint32_t v = first; v < last; ++v) {
    if (p.vertex_corner[v] == kNone) {  // in no face: carried along
      store(s.dst, v, at(s.src, v));
      continue;
    }
    const Ring r = walk(s, v, catmark, s.creased);
    const uint32_t n = r.num_faces < uint32_t(kMaxValence) ? r.num_faces : uint32_t(kMaxValence);
    const float pvs = s.creased ? p.sharpness_of_vertex(v) : 0.0f;
    const float cvs = s.creased ? s.c->sharpness_of_vertex(v) : 0.0f;
    const float centre = s.weights->vertex[n], ring = s.weights->ring[n];
    const refined::RuleMask k = refined::vertex_point_mask({centre, ring, catmark ? ring : 0.0f}, pvs, r.parent_sharp, cvs,
                                                           r.child_sharp, r.transitions, r.transition_sum);
    store(s.dst, v, apply(k, r, at(s.src, v)));
  }
}

// Sdc::Scheme::ComputeEdgeVertexMask: smooth (catmark: the two new face points; Loop: the two
// opposite vertices), the midpoint where both halves stay sharp, else the blend by the sharpness.
P3 edge_point(const Step& s, uint32_t e, bool catmark) {
  const Level& p = *s.p;
  const uint32_t h = p.edge_corner[e], t = p.twin[h];
  const P3 a = at(s.src, p.vert[h]), b = at(s.src, p.vert[p.next(h)]);
  const float sharp = s.creased ? p.edge_sharpness[e] : 0.0f;
  float vw = catmark ? 0.25f : 0.375f, fw = catmark ? 0.25f : 0.125f;
  if (sharp > 0.0f) {
    const float c0 = s.c->sharpness_of_edge(2 * e), c1 = s.c->sharpness_of_edge(2 * e + 1);
    if (c0 > 0.0f && c1 > 0.0f) return (a + b) * 0.5f;
    const float cw = 1.0f - sharp;
    vw = sharp * 0.5f + cw * vw;
    fw = fw * cw;
  }
  if (t == kNone) return (a + b) * 0.5f;  // boundaries are infinitely sharp: not reached
  const P3 f0 = catmark ? at(s.dst, p.num_vertices + p.face(h)) : at(s.src, p.vert[p.prev(h)]);
  const P3 f1 = catmark ? at(s.dst, p.num_vertices + p.face(t)) : at(s.src, p.vert[p.prev(t)]);
  return (a + b) * vw + (f0 + f1) * fw;
}

}  // namespace

SmoothWeights smooth_weights(SubdivisionRule rule) {
  SmoothWeights w;
  w.vertex.assign(kMaxValence + 1, 0.0f);
  w.ring.assign(kMaxValence + 1, 0.0f);
  w.inverse.assign(kMaxValence + 1, 0.0f);
  for (int n = 1; n <= kMaxValence; ++n) {
    w.inverse[n] = 1.0f / float(n);
    if (rule == SubdivisionRule::CatmullClark) {
      w.vertex[n] = float(n - 2) / float(n);
      w.ring[n] = 1.0f / float(n * n);
    } else if (n == 6) {
      w.vertex[n] = 0.625f, w.ring[n] = 0.0625f;
    } else {
      const double inv = 1.0 / n, beta = 0.25 * std::cos(M_PI * 2.0 * inv) + 0.375;
      w.ring[n] = float((0.625 - beta * beta) * inv);
      w.vertex[n] = float(1.0 - double(w.ring[n]) * n);
    }
  }
  return w;
}

void catmark_face_points(const Step& s, uint32_t first, uint32_t last) {
  const Level& p = *s.p;
  for (uint32_t f = first; f < last; ++f) {
    const uint32_t a = p.face_size ? f * p.face_size : p.face_first[f];
    const uint32_t n = p.face_size ? p.face_size : p.face_first[f + 1] - a;
    P3 sum = at(s.src, p.vert[a]);
    for (uint32_t i = 1; i < n; ++i) sum = sum + at(s.src, p.vert[a + i]);
    // 1 / n as Far's face mask has it (a table, as the shaders read it: GLSL's division is not exact)
    store(s.dst, p.num_vertices + f, sum * s.weights->inverse[n]);
  }
}

void catmark_edge_points(const Step& s, uint32_t first, uint32_t last) {
  const uint32_t base = s.p->num_vertices + s.p->num_faces;
  for (uint32_t e = first; e < last; ++e) store(s.dst, base + e, edge_point(s, e, true));
}

void catmark_vertex_points(const Step& s, uint32_t first, uint32_t last) { vertex_points(s, first, last, true); }

void loop_edge_points(const Step& s, uint32_t first, uint32_t last) {
  const uint32_t base = s.p->num_vertices;
  for (uint32_t e = first; e < last; ++e) store(s.dst, base + e, edge_point(s, e, false));
}

void loop_vertex_points(const Step& s, uint32_t first, uint32_t last) { vertex_points(s, first, last, false); }

void refine_points(const Step& s, SubdivisionRule rule, bool parallel) {
  auto run = [&](void (*pass)(const Step&, uint32_t, uint32_t), uint32_t count) {
    if (!parallel) return pass(s, 0, count);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, count, 2048),
                      [&](const tbb::blocked_range<uint32_t>& r) { pass(s, r.begin(), r.end()); });
  };
  if (rule == SubdivisionRule::CatmullClark) {
    run(catmark_face_points, s.p->num_faces);
    run(catmark_edge_points, s.p->num_edges);
    run(catmark_vertex_points, s.p->num_vertices);
  } else {
    run(loop_edge_points, s.p->num_edges);
    run(loop_vertex_points, s.p->num_vertices);
  }
}

}  // namespace sdb::halfedge
