#include "schemes/edgefriend/rules.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "harness/refined/float3.h"
#include "harness/refined/vertex_rule.h"

namespace sdb::edgefriend {
namespace {

using refined::P3;
using refined::at;
using refined::operator+;
using refined::operator*;

inline void store(const Step& s, uint32_t i, P3 v) {
  const uint32_t j = s.out_index ? s.out_index[i] : i;
  if (j != kNone) s.dst[j] = {v.x, v.y, v.z};
}

using refined::kCornerRule, refined::kCreaseRule, refined::kDartRule, refined::kSmoothRule, refined::vertex_rule;

// What the vertex rules read of a ring, in one walk through the friends (the paper's valence
// loop): the sums of the edges' other ends and of the diagonals, and the other ends of the sharp
// edges before and after the step.
struct Ring {
  P3 edges{0, 0, 0}, diagonals{0, 0, 0}, parent_ends{0, 0, 0}, child_ends{0, 0, 0};
  uint32_t n = 0;
  int parent_sharp = 0, child_sharp = 0, transitions = 0;
  float transition_sum = 0;
};

Ring walk(const Step& s, uint32_t start) {
  const Level& p = *s.p;
  Ring r;
  uint32_t c = start;
  do {
    ++r.n;
    // Corner c's edge to c ^ 3 is one its quad owns (1-2 or 3-0); its diagonal is c ^ 2.
    const P3 e = at(s.src, p.indices[c ^ 3u]);
    r.edges = r.edges + e;
    r.diagonals = r.diagonals + at(s.src, p.indices[c ^ 2u]);
    const Friends& f = p.friends[c >> 2];
    const bool edge30 = ((c + 1) & 2u) == 0;  // slot 0 or 3
    const uint32_t fr = edge30 ? f.friend1 : f.friend0;
    if (p.creased) {
      const float sharp = edge30 ? f.sharpness1 : f.sharpness0;
      if (sharp > 0.0f) {
        r.parent_ends = r.parent_ends + e, ++r.parent_sharp;
        if (decay(sharp) > 0.0f) r.child_ends = r.child_ends + e, ++r.child_sharp;
        else r.transition_sum += sharp, ++r.transitions;
      }
    }
    c = 2 * fr + (c & 1u);
  } while (c != start && r.n <= 4 * p.num_quads);
  return r;
}

// Sdc's vertex-point mask on the ring (refined::vertex_point_mask), its face sum the diagonals'.
refined::RuleMask vertex_mask(const Ring& r, float parent_vs, const SmoothWeights& w) {
  const uint32_t n = r.n < uint32_t(kMaxValence) ? r.n : uint32_t(kMaxValence);  // past it: a ghost face's point
  const refined::RuleMask smooth{w.vertex[n], w.edge[n], w.diagonal[n]};
  return refined::vertex_point_mask(smooth, parent_vs, r.parent_sharp, decay(parent_vs), r.child_sharp, r.transitions,
                                    r.transition_sum);
}

void vertex_point(const Step& s, uint32_t v) {
  const Level& p = *s.p;
  const uint32_t start = p.vertex_corner[v], to = child_of_vertex(v, p.num_quads);
  if (start == kNone) return store(s, to, {0, 0, 0});  // in no quad: no point (never output)
  const Ring r = walk(s, start);
  const float vs = p.vertex_sharpness.empty() ? 0.0f : p.vertex_sharpness[v];
  const refined::RuleMask k = vertex_mask(r, vs, *s.weights);
  const P3 centre = at(s.src, v);
  store(s, to, ((r.edges * k.edges + r.diagonals * k.faces) + (r.parent_ends * k.parent_ends + r.child_ends * k.child_ends)) +
                   centre * k.vertex);
}

// Sdc::Scheme::ComputeEdgeVertexMask on edge a-b between quads with opposite sides c-d and e-f
// (the quad's own other two corners, the friend's): 3/8, 1/16, 1/16 smooth; the midpoint where
// both halves stay sharp; else the blend by the sharpness.
P3 edge_point(P3 a, P3 b, P3 near, P3 far, float sharp) {
  float vw = 0.375f, ow = 0.0625f;
  if (sharp > 0.0f) {
    if (decay(sharp) > 0.0f) return (a + b) * 0.5f;
    const float cw = 1.0f - sharp;
    vw = sharp * 0.5f + cw * vw;
    ow = ow * cw;
  }
  return (a + b) * vw + (near + far) * ow;
}

void quad_points(const Step& s, uint32_t q) {
  const Level& p = *s.p;
  const uint32_t* x = &p.indices[4 * uint64_t(q)];
  const P3 A = at(s.src, x[0]), B = at(s.src, x[1]), C = at(s.src, x[2]), D = at(s.src, x[3]);
  const Friends& f = p.friends[q];
  // The friend's two corners away from the shared edge: its 2 (1 - side) and 2 (1 - side) + 1.
  const uint32_t* y0 = &p.indices[4 * uint64_t(f.friend0 >> 1) + 2 * (1 - (f.friend0 & 1u))];
  const uint32_t* y1 = &p.indices[4 * uint64_t(f.friend1 >> 1) + 2 * (1 - (f.friend1 & 1u))];
  const float s0 = p.creased ? f.sharpness0 : 0.0f, s1 = p.creased ? f.sharpness1 : 0.0f;
  store(s, 4 * q + 1, (((A + B) + C) + D) * 0.25f);
  store(s, 4 * (f.friend0 >> 1) + 2 + (f.friend0 & 1u), edge_point(B, C, A + D, at(s.src, y0[0]) + at(s.src, y0[1]), s0) );
  store(s, 4 * (f.friend1 >> 1) + 2 + (f.friend1 & 1u), edge_point(D, A, B + C, at(s.src, y1[0]) + at(s.src, y1[1]), s1));
}

}  // namespace

SmoothWeights smooth_weights() {
  SmoothWeights w;
  w.vertex.assign(kMaxValence + 1, 0.0f);
  w.edge.assign(kMaxValence + 1, 0.0f);
  w.diagonal.assign(kMaxValence + 1, 0.0f);
  for (int n = 1; n <= kMaxValence; ++n) {
    const double nn = double(n) * n;
    w.vertex[n] = float(1.0 - 7.0 / (4.0 * n));
    w.edge[n] = float(1.5 / nn);
    w.diagonal[n] = float(0.25 / nn);
  }
  return w;
}

uint32_t invocations(const Level& p) { return p.num_vertices > p.num_quads ? p.num_vertices : p.num_quads; }

void refine_points(const Step& s, uint32_t first, uint32_t last) {
  const Level& p = *s.p;
  for (uint32_t i = first; i < last; ++i) {
    if (i < p.num_vertices) vertex_point(s, i);
    if (i < p.num_quads) quad_points(s, i);
  }
}

void refine_level_points(const Step& s, bool parallel) {
  const uint32_t n = invocations(*s.p);
  if (!parallel) return refine_points(s, 0, n);
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, 2048),
                    [&](const tbb::blocked_range<uint32_t>& r) { refine_points(s, r.begin(), r.end()); });
}

}  // namespace sdb::edgefriend
