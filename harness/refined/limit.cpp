#include "harness/refined/limit.h"

#include <opensubdiv/sdc/catmarkScheme.h>
#include <opensubdiv/sdc/crease.h>
#include <opensubdiv/sdc/loopScheme.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <tuple>

#include "harness/mesh/sdc_mask.h"
#include "harness/refined/exact_masks.h"
#include "harness/refined/float3.h"

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

// Position, first and second tangent masks of one vertex, as Sdc fills them (harness/mesh/sdc_mask.h);
// weights a mask leaves unset stay 0.
struct Masks {
  int edges = 0, faces = 0;
  SdcMask position, first, second;
  // Weight of ring slot `slot` in mask k: 0 the vertex, 1 + i edge i's end, 1 + edges + i face i's corner.
  float at(int k, int slot) const {
    const SdcMask& m = k == 0 ? position : k == 1 ? first : second;
    if (slot == 0) return m.VertexWeight(0);
    return slot <= edges ? m.EdgeWeight(slot - 1) : m.FaceWeight(slot - 1 - edges);
  }
};

template <Sdc::SchemeType kType>
Masks limit_masks(const Hood& hood, Sdc::Crease::Rule rule) {
  const int reserve = std::max(hood.GetNumEdges(), hood.GetNumFaces());
  Masks m{hood.GetNumEdges(), hood.GetNumFaces(), SdcMask(reserve), SdcMask(reserve), SdcMask(reserve)};
  Sdc::Scheme<kType>(Sdc::Options()).ComputeVertexLimitMask(hood, m.position, m.first, m.second, rule);
  // Face weights are for the opposite vertices.
  for (const SdcMask* k : {&m.position, &m.first, &m.second})
    if (k->GetNumFaceWeights() > 0 && k->AreFaceWeightsForFaceCenters())
      throw std::logic_error("a limit mask with face-centre weights");
  return m;
}

bool regular(const FaceLevel& l, const Ring& r, int sharp_edges, float vertex_sharpness) {
  const size_t valence = l.face_size == 4 ? 4 : 6;
  // (A dart, one sharp edge, is not: Far's masks take it as smooth, which is not its limit.)
  return !r.boundary() && r.corners.size() == valence && sharp_edges == 0 && vertex_sharpness <= 0.0f;
}

Point3 unit_normal(const float a[3], const float b[3]) {
  const float c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  const float len2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
  const float k = len2 > 0.0f ? 1.0f / std::sqrt(len2) : 0.0f;
  return {c[0] * k, c[1] * k, c[2] * k};
}

// A special vertex's entries from exact masks on its disk's slots: the face-opposite vertices,
// the edges' ends, the vertex (PrimvarRefiner::Limit's order, as Sdc's masks are entered).
void add_exact(SpecialTable& plan, const FaceLevel& l, const Ring& r, const RingDisk& d, const RingMasks& m, uint32_t v,
               uint32_t output) {
  const bool catmark = l.face_size == 4;
  plan.vertex.push_back(output);
  auto add = [&](uint32_t vertex, int slot) {
    plan.ring.push_back(vertex);
    plan.weights.push_back(static_cast<float>(m.position[slot]));
    plan.weights.push_back(static_cast<float>(m.first[slot]));
    plan.weights.push_back(static_cast<float>(m.second[slot]));
  };
  if (catmark)
    for (int i = 0; i < d.faces; ++i) add(l.verts[next_corner(next_corner(r.corners[i], 4), 4)], 1 + d.edges + i);
  for (int i = 0; i < d.faces; ++i) add(l.verts[next_corner(r.corners[i], l.face_size)], 1 + i);
  if (r.boundary()) add(l.verts[r.trailing], d.edges);
  add(v, 0);
  plan.begin.push_back(static_cast<uint32_t>(plan.ring.size()));
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

namespace {

// The lowest corner at every vertex: the one its SurfaceCoord is taken from (coords.h), whose face
// names the side a normal is judged on.
std::vector<uint32_t> first_corners(const FaceLevel& l) {
  std::vector<uint32_t> at(l.num_vertices, kNone);
  for (uint64_t c = l.num_corners; c-- > 0;) at[l.verts[c]] = static_cast<uint32_t>(c);
  return at;
}

// The vertex's ring as exact_masks.h takes it, on the side of the face of corner `first`.
RingDisk disk_of(const FaceLevel& l, const Ring& r, const std::vector<float>& sharpness, float vertex_sharpness,
                 uint32_t first) {
  RingDisk d;
  d.edges = static_cast<int>(r.edges());
  d.faces = static_cast<int>(r.corners.size());
  d.edge_sharpness = sharpness;
  d.vertex_sharpness = vertex_sharpness;
  const uint32_t face = first / l.face_size;
  for (size_t i = 0; i < r.corners.size(); ++i)
    if (r.corners[i] / l.face_size == face) d.side = static_cast<int>(i);
  return d;
}

// A vertex's ring from corner `start` (vertex_corners'), its edges' sharpness in ring order.
struct VertexRing {
  Ring r;
  std::vector<float> sharpness;
  float vertex_sharpness = 0;
  int sharp = 0;      // sharp edges
  bool semi = false;  // an edge or the vertex semi-sharp
};

VertexRing ring_at(const FaceLevel& l, uint32_t v, uint32_t start) {
  VertexRing out;
  out.r = walk(l, start);
  for (uint32_t c : out.r.corners) out.sharpness.push_back(l.edge_sharpness ? l.edge_sharpness(c) : 0.0f);
  if (out.r.boundary()) out.sharpness.push_back(l.edge_sharpness ? l.edge_sharpness(out.r.trailing) : 0.0f);
  const float vs = l.vertex_sharpness ? l.vertex_sharpness(v) : 0.0f;
  out.vertex_sharpness = vs;
  out.semi = vs > 0.0f && vs < kInfiniteSharpness;
  for (float s : out.sharpness) out.sharp += s > 0.0f, out.semi = out.semi || (s > 0.0f && s < kInfiniteSharpness);
  return out;
}

// Exact masks by ring, made once per kind of ring (a crease's 2^k vertices share one).
class ExactMaskCache {
 public:
  ExactMaskCache(SubdivisionRule rule, const Sdc::Options& options) : rule_(rule), options_(options) {}
  const RingMasks& at(const RingDisk& d) {
    auto key = std::make_tuple(d.edges, d.faces, d.edge_sharpness, d.vertex_sharpness, d.side);
    auto it = cache_.find(key);
    if (it == cache_.end()) it = cache_.emplace(key, exact_ring_masks(d, rule_, options_)).first;
    return it->second;
  }

 private:
  SubdivisionRule rule_;
  Sdc::Options options_;
  std::map<std::tuple<int, int, std::vector<float>, float, int>, RingMasks> cache_;
};

}  // namespace

// Where the early level has last-level vertex v: its ring's exact masks there, into plan.early.
class EarlyRings {
 public:
  EarlyRings(const EarlyLevel* early, const FaceLevel& last) {
    if (!early || !early->level) return;
    level_ = early->level;
    if (level_->face_size != last.face_size || early->last_of.size() != level_->num_vertices)
      throw std::invalid_argument("plan_limit: an early level of other faces or vertices");
    early_of_.assign(last.num_vertices, kNone);
    for (uint32_t u = 0; u < level_->num_vertices; ++u)
      if (early->last_of[u] != kNone) early_of_.at(early->last_of[u]) = u;
    corners_ = vertex_corners(*level_);
    first_ = first_corners(*level_);
  }

  bool add(uint32_t v, ExactMaskCache& exact, SpecialTable& table) const {
    const uint32_t u = early_of_.empty() ? kNone : early_of_[v];
    if (u == kNone || corners_[u] == kNone) return false;
    const VertexRing er = ring_at(*level_, u, corners_[u]);
    const RingDisk disk = disk_of(*level_, er.r, er.sharpness, er.vertex_sharpness, first_[u]);
    const RingMasks& m = exact.at(disk);
    if (m.first.empty()) return false;
    add_exact(table, *level_, er.r, disk, m, u, v);
    return true;
  }

 private:
  const FaceLevel* level_ = nullptr;
  std::vector<uint32_t> early_of_, corners_, first_;
};

LimitPlan plan_limit(const FaceLevel& l, SubdivisionRule rule, const Sdc::Options& options, const EarlyLevel* early) {
  const bool catmark = rule == SubdivisionRule::CatmullClark;
  if (l.face_size != (catmark ? 4u : 3u)) throw std::invalid_argument("plan_limit: faces of the wrong size for the rule");
  LimitPlan plan;
  plan.face_size = l.face_size;
  plan.num_vertices = l.num_vertices;
  plan.ring_size = catmark ? 8 : 6;
  const std::vector<uint32_t> corners = vertex_corners(l), first = first_corners(l);
  ExactMaskCache exact(rule, options);
  const EarlyRings early_rings(early, l);
  plan.regular_ring.assign(size_t(plan.ring_size) * l.num_vertices, kNone);
  for (uint32_t v = 0; v < l.num_vertices; ++v) {
    const uint32_t start = corners[v];
    if (start == kNone) continue;  // in no face: no limit (Far leaves it), none written
    VertexRing vr = ring_at(l, v, start);
    Ring& r = vr.r;
    std::vector<float>& sharpness = vr.sharpness;
    const float vs = vr.vertex_sharpness;
    if (regular(l, r, vr.sharp, vs)) {
      uint32_t* ring = &plan.regular_ring[size_t(plan.ring_size) * v];
      for (size_t i = 0; i < r.corners.size(); ++i) {
        const uint32_t nc = next_corner(r.corners[i], l.face_size);
        ring[i] = l.verts[nc];
        if (catmark) ring[4 + i] = l.verts[next_corner(nc, 4)];
      }
      continue;
    }
    if (early_rings.add(v, exact, plan.early)) continue;
    const RingDisk disk = disk_of(l, r, sharpness, vs, first[v]);
    if (vr.semi || !far_masks_exact(disk, rule)) {
      const RingMasks& m = exact.at(disk);
      if (!m.first.empty()) {
        add_exact(plan.special, l, r, disk, m, v, v);
        continue;
      }  // no tangent plane the ring's matrix shows (valence 2): Far's masks, the limit has no normal
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
    const Hood hood(static_cast<int>(r.edges()), static_cast<int>(r.corners.size()), vs, sharpness.data());
    const Masks masks =
        catmark ? limit_masks<Sdc::SCHEME_CATMARK>(hood, vrule) : limit_masks<Sdc::SCHEME_LOOP>(hood, vrule);
    SpecialTable& table = plan.special;
    table.vertex.push_back(v);
    auto add = [&](uint32_t vertex, int slot) {
      table.ring.push_back(vertex);
      for (int k = 0; k < 3; ++k) table.weights.push_back(masks.at(k, slot));
    };
    if (catmark)
      for (size_t i = 0; i < r.corners.size(); ++i) {
        const uint32_t c = r.corners[i];
        add(l.verts[next_corner(next_corner(c, 4), 4)], 1 + masks.edges + static_cast<int>(i));
      }
    for (size_t i = 0; i < r.corners.size(); ++i) add(l.verts[next_corner(r.corners[i], l.face_size)], 1 + static_cast<int>(i));
    if (r.boundary()) add(l.verts[r.trailing], masks.edges);
    add(v, 0);
    table.begin.push_back(static_cast<uint32_t>(table.ring.size()));
  }
  return plan;
}


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

void project_special(const SpecialTable& table, const float* points, const Projection& pr, uint32_t first, uint32_t last) {
  const P3 origin{pr.origin[0], pr.origin[1], pr.origin[2]};
  for (uint32_t i = first; i < last; ++i) {
    P3 pos{0, 0, 0}, t1{0, 0, 0}, t2{0, 0, 0};
    for (uint32_t k = table.begin[i]; k < table.begin[i + 1]; ++k) {
      const P3 p = load(points, pr.stride, table.ring[k]);
      const float* w = &table.weights[3 * size_t(k)];
      pos = pos + p * w[0];
      t1 = t1 + p * w[1];
      t2 = t2 + p * w[2];
    }
    pos = pos + origin;
    const uint32_t v = table.vertex[i];
    pr.positions[v] = {pos.x, pos.y, pos.z};
    const float a[3] = {t1.x, t1.y, t1.z}, b[3] = {t2.x, t2.y, t2.z};
    pr.normals[v] = unit_normal(a, b);
  }
}

void project(const LimitPlan& plan, const Projection& p, bool parallel) {
  if (plan.early.size() > 0 && !p.early_points) throw std::invalid_argument("project: the plan reads an early level");
  if (!parallel) {
    project_regular(plan, p, 0, plan.num_vertices);
    project_special(plan.special, p.points, p, 0, plan.special.size());
    project_special(plan.early, p.early_points, p, 0, plan.early.size());
    return;
  }
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, plan.num_vertices, 4096),
                    [&](const tbb::blocked_range<uint32_t>& r) { project_regular(plan, p, r.begin(), r.end()); });
  for (const auto& [table, points] : {std::pair{&plan.special, p.points}, std::pair{&plan.early, p.early_points}})
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, table->size(), 256), [&, t = table, pts = points](const tbb::blocked_range<uint32_t>& r) {
      project_special(*t, pts, p, r.begin(), r.end());
    });
}

}  // namespace sdb::refined
