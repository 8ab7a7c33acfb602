#include "harness/refined/limit.h"

#include <opensubdiv/sdc/catmarkScheme.h>
#include <opensubdiv/sdc/crease.h>
#include <opensubdiv/sdc/loopScheme.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace sdb::refined {
namespace {

namespace Sdc = OpenSubdiv::Sdc;

// The ring of a vertex as Far orders it: edges counter-clockwise from the leading one (at a
// boundary, the boundary edge whose face follows it), face i between edges i and i + 1.
struct Ring {
  std::vector<uint32_t> corners;  // outgoing corner of each face, in order
  uint32_t trailing = kNone;      // at a boundary: the corner whose edge ends at the vertex
  bool boundary() const { return trailing != kNone; }
  size_t edges() const { return corners.size() + boundary(); }
};

Ring walk(const FaceLevel& l, uint32_t start) {
  Ring r;
  uint32_t c = start;
  do {
    r.corners.push_back(c);
    const uint32_t p = prev_corner(c, l.face_size), t = l.twin[p];
    if (t == kNone) {
      r.trailing = p;
      break;
    }
    c = t;
  } while (c != start && r.corners.size() <= l.num_corners);
  return r;
}

// Sdc's neighbourhood of a vertex for its limit masks: counts and edge sharpness in ring order.
class Hood {
 public:
  Hood(int edges, int faces, float vertex_sharpness, const float* edge_sharpness)
      : edges_(edges), faces_(faces), vertex_sharpness_(vertex_sharpness), edge_sharpness_(edge_sharpness) {}
  int GetNumEdges() const { return edges_; }
  int GetNumFaces() const { return faces_; }
  float GetSharpness() const { return vertex_sharpness_; }
  float* GetSharpnessPerEdge(float s[]) const {
    for (int i = 0; i < edges_; ++i) s[i] = edge_sharpness_[i];
    return s;
  }

 private:
  int edges_, faces_;
  float vertex_sharpness_;
  const float* edge_sharpness_;
};

// Sdc's MASK concept over caller-owned arrays.
class Mask {
 public:
  typedef float Weight;
  Mask(float* v, float* e, float* f) : v_(v), e_(e), f_(f) {}
  int GetNumVertexWeights() const { return nv_; }
  int GetNumEdgeWeights() const { return ne_; }
  int GetNumFaceWeights() const { return nf_; }
  void SetNumVertexWeights(int n) { nv_ = n; }
  void SetNumEdgeWeights(int n) { ne_ = n; }
  void SetNumFaceWeights(int n) { nf_ = n; }
  const float& VertexWeight(int i) const { return v_[i]; }
  const float& EdgeWeight(int i) const { return e_[i]; }
  const float& FaceWeight(int i) const { return f_[i]; }
  float& VertexWeight(int i) { return v_[i]; }
  float& EdgeWeight(int i) { return e_[i]; }
  float& FaceWeight(int i) { return f_[i]; }
  bool AreFaceWeightsForFaceCenters() const { return centres_; }
  void SetFaceWeightsForFaceCenters(bool on) { centres_ = on; }

 private:
  float *v_, *e_, *f_;
  int nv_ = 0, ne_ = 0, nf_ = 0;
  bool centres_ = false;
};

struct Masks {
  std::vector<float> w;  // three masks of 1 + edges + faces weights each
  int edges = 0, faces = 0;
  float* at(int mask) { return w.data() + mask * (1 + edges + faces); }
};

template <Sdc::SchemeType kType>
void limit_masks(const Hood& hood, Sdc::Crease::Rule rule, Masks& m) {
  const int size = 1 + m.edges + m.faces;
  m.w.assign(3 * size, 0.0f);
  Mask pos(m.at(0), m.at(0) + 1, m.at(0) + 1 + m.edges), t1(m.at(1), m.at(1) + 1, m.at(1) + 1 + m.edges),
      t2(m.at(2), m.at(2) + 1, m.at(2) + 1 + m.edges);
  Sdc::Scheme<kType>(Sdc::Options()).ComputeVertexLimitMask(hood, pos, t1, t2, rule);
  // Weights a mask did not set stay 0 (assign above); face weights are for the opposite vertices.
  for (Mask* k : {&pos, &t1, &t2})
    if (k->GetNumFaceWeights() > 0 && k->AreFaceWeightsForFaceCenters())
      throw std::logic_error("a limit mask with face-centre weights");
}

bool regular(const FaceLevel& l, const Ring& r, int sharp_edges, float vertex_sharpness) {
  const size_t valence = l.face_size == 4 ? 4 : 6;
  return !r.boundary() && r.corners.size() == valence && sharp_edges <= 1 && vertex_sharpness <= 0.0f;
}

Point3 unit_normal(const float a[3], const float b[3]) {
  const float c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  const float len2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
  const float k = len2 > 0.0f ? 1.0f / std::sqrt(len2) : 0.0f;
  return {c[0] * k, c[1] * k, c[2] * k};
}

}  // namespace

std::vector<uint32_t> vertex_corners(const FaceLevel& l) {
  std::vector<uint32_t> at(l.num_vertices, kNone);
  for (uint64_t c = 0; c < l.num_corners; ++c) {
    uint32_t& a = at[l.verts[c]];
    if (a == kNone || l.twin[c] == kNone) a = static_cast<uint32_t>(c);
  }
  return at;
}

LimitPlan plan_limit(const FaceLevel& l, SubdivisionRule rule) {
  const bool catmark = rule == SubdivisionRule::CatmullClark;
  if (l.face_size != (catmark ? 4u : 3u)) throw std::invalid_argument("plan_limit: faces of the wrong size for the rule");
  LimitPlan plan;
  plan.face_size = l.face_size;
  plan.num_vertices = l.num_vertices;
  plan.ring_size = catmark ? 8 : 6;
  const std::vector<uint32_t> corners = vertex_corners(l);
  plan.regular_ring.assign(size_t(plan.ring_size) * l.num_vertices, kNone);
  std::vector<float> sharpness;
  Masks masks;
  for (uint32_t v = 0; v < l.num_vertices; ++v) {
    const uint32_t start = corners[v];
    if (start == kNone) continue;  // in no face: no limit (Far leaves it), none written
    Ring r = walk(l, start);
    sharpness.clear();
    for (uint32_t c : r.corners) sharpness.push_back(l.edge_sharpness ? l.edge_sharpness(c) : 0.0f);
    if (r.boundary()) sharpness.push_back(l.edge_sharpness ? l.edge_sharpness(r.trailing) : 0.0f);
    const float vs = l.vertex_sharpness ? l.vertex_sharpness(v) : 0.0f;
    int sharp = 0;
    bool semi = vs > 0.0f && vs < kInfiniteSharpness;
    for (float s : sharpness) {
      sharp += s > 0.0f;
      if (s > 0.0f && s < kInfiniteSharpness) semi = true, plan.largest_sharpness_left = std::max(plan.largest_sharpness_left, s);
    }
    if (vs < kInfiniteSharpness) plan.largest_sharpness_left = std::max(plan.largest_sharpness_left, vs);
    plan.semi_sharp_vertices += semi;
    if (regular(l, r, sharp, vs)) {
      uint32_t* ring = &plan.regular_ring[size_t(plan.ring_size) * v];
      for (size_t i = 0; i < r.corners.size(); ++i) {
        const uint32_t nc = next_corner(r.corners[i], l.face_size);
        ring[i] = l.verts[nc];
        if (catmark) ring[4 + i] = l.verts[next_corner(nc, 4)];
      }
      continue;
    }
    const Sdc::Crease::Rule vrule =
        Sdc::Crease().DetermineVertexVertexRule(vs, static_cast<int>(sharpness.size()), sharpness.data());
    if (vrule == Sdc::Crease::RULE_CREASE && !r.boundary()) {
      // An interior crease has a side: Sdc's tangents span the faces from the ring's first sharp
      // edge to its second. Start the ring at the sharp edge before the vertex's first corner
      // (turning clockwise, c -> next(twin(c))), so that the side is the face its SurfaceCoord
      // names (coords.h: the first corner at the vertex); Far's own side is its edge order's.
      uint32_t c = start;
      while (!(l.edge_sharpness(c) > 0.0f)) c = next_corner(l.twin[c], l.face_size);
      r = walk(l, c);
      sharpness.clear();
      for (uint32_t k : r.corners) sharpness.push_back(l.edge_sharpness(k));
    }
    masks.edges = static_cast<int>(r.edges());
    masks.faces = static_cast<int>(r.corners.size());
    const Hood hood(masks.edges, masks.faces, vs, sharpness.data());
    if (catmark) limit_masks<Sdc::SCHEME_CATMARK>(hood, vrule, masks);
    else limit_masks<Sdc::SCHEME_LOOP>(hood, vrule, masks);
    plan.special.push_back(v);
    auto add = [&](uint32_t vertex, int slot) {
      plan.ring.push_back(vertex);
      for (int k = 0; k < 3; ++k) plan.weights.push_back(masks.at(k)[slot]);
    };
    if (catmark)
      for (size_t i = 0; i < r.corners.size(); ++i) {
        const uint32_t c = r.corners[i];
        add(l.verts[next_corner(next_corner(c, 4), 4)], 1 + masks.edges + static_cast<int>(i));
      }
    for (size_t i = 0; i < r.corners.size(); ++i) add(l.verts[next_corner(r.corners[i], l.face_size)], 1 + static_cast<int>(i));
    if (r.boundary()) add(l.verts[r.trailing], masks.edges);
    add(v, 0);
    plan.begin.push_back(static_cast<uint32_t>(plan.ring.size()));
  }
  return plan;
}

namespace {

struct P3 {
  float x, y, z;
};
inline P3 load(const float* points, uint32_t stride, uint32_t v) {
  const float* p = points + size_t(v) * stride;
  return {p[0], p[1], p[2]};
}
inline P3 operator+(P3 a, P3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline P3 operator-(P3 a, P3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline P3 operator*(P3 a, float w) { return {a.x * w, a.y * w, a.z * w}; }

}  // namespace

// Sdc's constant masks of a regular vertex (catmarkScheme.h, loopScheme.h), their sums ordered as
// PrimvarRefiner::Limit's: faces, then edges, then the vertex.
RegularConstants regular_constants(uint32_t face_size) {
  if (face_size == 4) return {{1.0f / 36.0f, 1.0f / 9.0f, 4.0f / 9.0f}};
  return {{1.0f / 12.0f, 0.5f, 0.866025403784438647f}};
}

void project_regular(const LimitPlan& plan, const Projection& p, uint32_t first, uint32_t last) {
  const RegularConstants rc = regular_constants(plan.face_size);
  const float k0 = rc.k[0], k1 = rc.k[1], k2 = rc.k[2];
  const uint32_t stride = p.stride, size = plan.ring_size;
  const float* points = p.points;
  const P3 origin{p.origin[0], p.origin[1], p.origin[2]};
  for (uint32_t v = first; v < last; ++v) {
    const uint32_t* ring = &plan.regular_ring[size_t(size) * v];
    if (ring[0] == kNone) continue;
    const P3 centre = load(points, stride, v);
    P3 pos, t1, t2;
    if (size == 8) {
      P3 e[4], d[4];
      for (int i = 0; i < 4; ++i) e[i] = load(points, stride, ring[i]), d[i] = load(points, stride, ring[4 + i]);
      pos = d[0] * k0 + d[1] * k0 + d[2] * k0 + d[3] * k0 + e[0] * k1 + e[1] * k1 + e[2] * k1 + e[3] * k1 + centre * k2;
      // tan1: faces (1, -1, -1, 1), edges (4, 0, -4, 0); tan2: faces (1, 1, -1, -1), edges (0, 4, 0, -4).
      const P3 d02 = d[0] - d[2], d13 = d[1] - d[3];
      t1 = (d02 - d13) + (e[0] - e[2]) * 4.0f;
      t2 = (d02 + d13) + (e[1] - e[3]) * 4.0f;
    } else {
      P3 e[6];
      for (int i = 0; i < 6; ++i) e[i] = load(points, stride, ring[i]);
      pos = e[0] * k0 + e[1] * k0 + e[2] * k0 + e[3] * k0 + e[4] * k0 + e[5] * k0 + centre * k1;
      // tan1: (1, .5, -.5, -1, -.5, .5); tan2: (0, r, r, 0, -r, -r), r = sqrt(3) / 2.
      const P3 d14 = e[1] - e[4], d25 = e[2] - e[5];
      t1 = (e[0] - e[3]) + (d14 - d25) * 0.5f;
      t2 = (d14 + d25) * k2;
    }
    pos = pos + origin;
    p.positions[v] = {pos.x, pos.y, pos.z};
    const float a[3] = {t1.x, t1.y, t1.z}, b[3] = {t2.x, t2.y, t2.z};
    p.normals[v] = unit_normal(a, b);
  }
}

void project_special(const LimitPlan& plan, const Projection& pr, uint32_t first, uint32_t last) {
  const P3 origin{pr.origin[0], pr.origin[1], pr.origin[2]};
  for (uint32_t i = first; i < last; ++i) {
    P3 pos{0, 0, 0}, t1{0, 0, 0}, t2{0, 0, 0};
    for (uint32_t k = plan.begin[i]; k < plan.begin[i + 1]; ++k) {
      const P3 p = load(pr.points, pr.stride, plan.ring[k]);
      const float* w = &plan.weights[3 * size_t(k)];
      pos = pos + p * w[0];
      t1 = t1 + p * w[1];
      t2 = t2 + p * w[2];
    }
    pos = pos + origin;
    const uint32_t v = plan.special[i];
    pr.positions[v] = {pos.x, pos.y, pos.z};
    const float a[3] = {t1.x, t1.y, t1.z}, b[3] = {t2.x, t2.y, t2.z};
    pr.normals[v] = unit_normal(a, b);
  }
}

void project(const LimitPlan& plan, const Projection& p, bool parallel) {
  const uint32_t specials = static_cast<uint32_t>(plan.special.size());
  if (!parallel) {
    project_regular(plan, p, 0, plan.num_vertices);
    project_special(plan, p, 0, specials);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, plan.num_vertices, 4096),
                    [&](const tbb::blocked_range<uint32_t>& r) { project_regular(plan, p, r.begin(), r.end()); });
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, specials, 256),
                    [&](const tbb::blocked_range<uint32_t>& r) { project_special(plan, p, r.begin(), r.end()); });
}

std::vector<std::string> semi_sharp_notes(const LimitPlan& plan, int depth) {
  if (plan.semi_sharp_vertices == 0) return {};
  char note[240];
  std::snprintf(note, sizeof note,
                "semi-sharp creases outlast depth %d (sharpness up to %.3g left at %llu vertices): projected with "
                "Far's limit masks there, which take it as infinite (not the limit)",
                depth, double(plan.largest_sharpness_left), static_cast<unsigned long long>(plan.semi_sharp_vertices));
  return {note};
}

}  // namespace sdb::refined
