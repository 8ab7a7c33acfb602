#include "harness/refined/exact_masks.h"

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyRefiner.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "harness/reference/local_mesh.h"
#include "harness/reference/ring_limit.h"

namespace sdb::refined {
namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

constexpr float kInfinite = 10.0f;  // Sdc::Crease::SHARPNESS_INFINITE

bool semi_sharp(float s) { return s > 0.0f && s < kInfinite; }

bool decays(const RingDisk& d) {
  return semi_sharp(d.vertex_sharpness) || std::any_of(d.edge_sharpness.begin(), d.edge_sharpness.end(), semi_sharp);
}

// A primvar of one double, for Far's refinement and limit of unit vectors: the weights.
struct Scalar {
  double x = 0;
  void Clear(void* = nullptr) { x = 0; }
  void AddWithWeight(const Scalar& s, float w) { x += s.x * double(w); }
};

using Matrix = std::vector<std::vector<double>>;  // [row][column]

// Values at the disk's slots of each unit vector's image: out[slot][column].
template <class Apply>
Matrix of_unit_vectors(int slots, Apply apply) {
  Matrix out(slots, std::vector<double>(slots, 0.0));
  for (int c = 0; c < slots; ++c) {
    const std::vector<double> image = apply(c);
    for (int r = 0; r < slots; ++r) out[r][c] = image[r];
  }
  return out;
}

// One level of the ring's refinement by Far (its semi-sharp rules, Chaikin's included): the
// matrix from the disk's slots to its child's, and the child's disk.
Matrix refine_disk(RingDisk& d, SubdivisionRule rule, const Sdc::Options& options) {
  const bool catmark = rule == SubdivisionRule::CatmullClark;
  const int slots = d.slots(catmark);
  auto refiner = refiner_of(ring_mesh(d.edges, d.faces, d.edge_sharpness, d.vertex_sharpness, catmark), rule, options);
  Far::TopologyRefiner::UniformOptions uniform(1);
  uniform.fullTopologyInLastLevel = true;
  refiner->RefineUniform(uniform);
  const Far::TopologyLevel &l0 = refiner->GetLevel(0), &l1 = refiner->GetLevel(1);
  std::vector<int> child(slots), child_edge(d.edges);
  const int centre = l0.GetVertexChildVertex(0);
  child[0] = centre;
  for (int i = 0; i < d.edges; ++i) {
    const int e = l0.FindEdge(0, 1 + i);
    if (e < 0) throw std::invalid_argument("exact_ring_masks: a ring Far does not build");
    child[1 + i] = l0.GetEdgeChildVertex(e);
    child_edge[i] = l1.FindEdge(centre, child[1 + i]);
  }
  for (int i = 0; catmark && i < d.faces; ++i) child[1 + d.edges + i] = l0.GetFaceChildVertex(i);
  Far::PrimvarRefiner primvar(*refiner);
  const Matrix s = of_unit_vectors(slots, [&](int c) {
    std::vector<Scalar> src(l0.GetNumVertices()), dst(l1.GetNumVertices());
    src[c].x = 1;
    Scalar* out = dst.data();
    primvar.Interpolate(1, src.data(), out);
    std::vector<double> image(slots);
    for (int r = 0; r < slots; ++r) image[r] = dst[child[r]].x;
    return image;
  });
  for (int i = 0; i < d.edges; ++i) d.edge_sharpness[i] = l1.GetEdgeSharpness(child_edge[i]);
  d.vertex_sharpness = l1.GetVertexSharpness(centre);
  return s;
}

// Weights in Far's ring order (ring_limit_vertices) as weights on the slots (the disk's local
// vertices are its slots).
std::vector<double> on_slots(const std::vector<double>& w, const std::vector<int>& order, int slots) {
  std::vector<double> out(slots, 0.0);
  for (size_t k = 0; k < w.size(); ++k) out[order[k]] += w[k];
  return out;
}

// The masks of a disk whose rules repeat, on its slots.
RingMasks stationary_masks(const RingDisk& d, SubdivisionRule rule, const Sdc::Options& options) {
  const bool catmark = rule == SubdivisionRule::CatmullClark;
  const int slots = d.slots(catmark);
  auto refiner = refiner_of(ring_mesh(d.edges, d.faces, d.edge_sharpness, d.vertex_sharpness, catmark), rule, options);
  const Far::TopologyLevel& l = refiner->GetLevel(0);
  RingMasks m;
  // Far's masks, as PrimvarRefiner::Limit applies them, by unit vectors.
  {
    Far::PrimvarRefiner primvar(*refiner);
    m.position.assign(slots, 0.0), m.first.assign(slots, 0.0), m.second.assign(slots, 0.0);
    for (int c = 0; c < slots; ++c) {
      std::vector<Scalar> src(l.GetNumVertices()), p(l.GetNumVertices()), t1(l.GetNumVertices()), t2(l.GetNumVertices());
      src[c].x = 1;
      Scalar *pp = p.data(), *a = t1.data(), *b = t2.data();
      primvar.Limit(src.data(), pp, a, b);
      m.position[c] = p[0].x, m.first[c] = t1[0].x, m.second[c] = t2[0].x;
    }
  }
  Far::ConstIndexArray ve = l.GetVertexEdges(0), vf = l.GetVertexFaces(0);
  const Sdc::Crease::Rule vrule = l.GetVertexRule(0);
  const bool boundary = l.IsVertexBoundary(0);
  int sharp = -1, inner_sharp = 0;
  for (int i = 0; i < ve.size(); ++i) {
    if (l.GetEdgeSharpness(ve[i]) > 0) sharp = i;
    inner_sharp += l.GetEdgeSharpness(ve[i]) > 0 && l.GetEdgeFaces(ve[i]).size() == 2;
  }
  const bool dart = vrule == Sdc::Crease::RULE_DART && !boundary;
  const bool valence2 = vrule == Sdc::Crease::RULE_SMOOTH && !boundary && ve.size() == 2;
  if (dart || valence2) {
    const int start = dart ? sharp : 0;
    m.position = on_slots(ring_limit_weights(l, options, catmark, 0, start), ring_limit_vertices(l, 0, catmark, start), slots);
  }
  const bool corner = l.GetVertexSharpness(0) > 0 && vf.size() > 1;
  const bool sided = inner_sharp >= 2 || (boundary && inner_sharp >= 1) || corner;
  const int next = (d.side + 1) % d.edges;
  if (sided && d.edge_sharpness[d.side] >= kInfinite && d.edge_sharpness[next] >= kInfinite) {
    // The face lies between two infinitely sharp edges: the ends of two crease curves, whose
    // directions are its side's tangents at every level (the corner rule keeps each edge's
    // direction; an eigenvector's Jordan block approaches them only as 1/K).
    std::fill(m.first.begin(), m.first.end(), 0.0), std::fill(m.second.begin(), m.second.end(), 0.0);
    m.first[0] = m.second[0] = -1, m.first[1 + d.side] = 1, m.second[1 + next] = 1;
  } else if (sided || !far_masks_exact(d, rule)) {
    const int face = static_cast<int>(std::find(vf.begin(), vf.end(), d.side) - vf.begin());
    const RingTangents t = ring_limit_tangents(l, options, catmark, 0, face);
    const std::vector<int> order = ring_limit_vertices(l, 0, catmark, 0);
    if (t.first.empty()) m.first.clear(), m.second.clear();
    else m.first = on_slots(t.first, order, slots), m.second = on_slots(t.second, order, slots);
  }
  return m;
}

// w^T s, a row vector through a matrix.
std::vector<double> times(const std::vector<double>& w, const Matrix& s) {
  std::vector<double> out(w.size(), 0.0);
  for (size_t r = 0; r < w.size(); ++r)
    for (size_t c = 0; c < w.size(); ++c) out[c] += w[r] * s[r][c];
  return out;
}

// Scaled to weights of 1 at most: a Jordan block's come out as large as 1e4, and composed ones as
// small as the refined ring is, and in float applied to float points they cancel.
void scale(std::vector<double>& w) {
  double big = 0;
  for (double x : w) big = std::max(big, std::abs(x));
  if (big > 0)
    for (double& x : w) x /= big;
}

}  // namespace

bool far_masks_exact(const RingDisk& d, SubdivisionRule rule) {
  const int side = rule == SubdivisionRule::Loop ? 3 : 2;
  const bool boundary = d.faces < d.edges;
  std::vector<int> sharp;
  for (int i = 0; i < d.edges; ++i)
    if (d.edge_sharpness[i] > 0.0f) sharp.push_back(i);
  if (d.vertex_sharpness > 0.0f || sharp.size() > 2) return boundary && d.faces == 1;
  if (sharp.size() == 2) return boundary ? d.faces == side : d.faces == 2 * side && sharp[1] - sharp[0] == side;
  return sharp.empty() && d.edges >= 3;
}

RingMasks exact_ring_masks(const RingDisk& disk, SubdivisionRule rule, const Sdc::Options& options) {
  RingDisk d = disk;
  std::vector<Matrix> steps;
  // Sharpness decays by at least one a level (Chaikin's too), from below 10.
  for (int level = 0; decays(d) && level < 12; ++level) steps.push_back(refine_disk(d, rule, options));
  RingMasks m = stationary_masks(d, rule, options);
  for (auto s = steps.rbegin(); s != steps.rend(); ++s) {
    m.position = times(m.position, *s);
    if (!m.first.empty()) m.first = times(m.first, *s), m.second = times(m.second, *s);
  }
  if (!m.first.empty()) scale(m.first), scale(m.second);
  return m;
}

}  // namespace sdb::refined
