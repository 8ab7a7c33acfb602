// The limit entries of a shape's tables (tables.h, LimitTable): positions, tangents per side,
// the regular tangents' fast path, and the output blocks that take them.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "harness/reference/ring_limit.h"
#include "schemes/fragments/table_builder.h"

namespace sdb::fragments::detail {

// Limit masks as PrimvarRefiner::Limit takes them: the last level's vertex rule, face weights
// on the vertex opposite in each face. Positions are one per vertex; tangents one per vertex
// and side: at a crease or corner the surface has a normal on each side, and each owned face
// takes the one of its own side (Far's masks give the side the vertex's ring starts in).
template <Sdc::SchemeType S>
void TableBuilder<S>::make_limit(ShapeTables& t) const {
  const Far::TopologyLevel& last = refiner_->GetLevel(depth_);
  const int bs = block_size(rule_, out_depth_), shift = depth_ - out_depth_, mask = (1 << shift) - 1;
  LimitTable& lim = t.limit;
  lim.tangent_begin.push_back(0);
  std::vector<char> control(refiner_->GetLevel(0).GetNumVertices(), 1);
  for (int l = 0; l < depth_; ++l) {
    const Far::TopologyLevel& level = refiner_->GetLevel(l);
    std::vector<char> next(refiner_->GetLevel(l + 1).GetNumVertices(), 0);
    for (int v = 0; v < level.GetNumVertices(); ++v)
      if (control[v] && level.GetVertexChildVertex(v) >= 0) next[level.GetVertexChildVertex(v)] = 1;
    control = std::move(next);
  }
  // One entry per block vertex, in block order, so that the output copy streams (a point shared by
  // two owned faces is computed in each, with the same rule: the same bits). Each vertex of a
  // block is a corner of every last-level face around it, all on the block's side.
  struct Corner {
    size_t at;
    int v, face;
  };
  std::vector<Corner> corners;
  for (const RegionFace& r : region_) {
    Far::ConstIndexArray fv = last.GetFaceVertices(r.face);
    for (int j = 0; j < fv.size(); ++j) {
      if ((r.uv[j][0] & mask) || (r.uv[j][1] & mask)) continue;  // between the output's grid points
      corners.push_back({static_cast<size_t>(r.owner) * bs +
                             block_index(rule_, out_depth_, r.uv[j][0] >> shift, r.uv[j][1] >> shift),
                         fv[j], r.face});
    }
  }
  std::sort(corners.begin(), corners.end(), [](const Corner& a, const Corner& b) { return a.at < b.at; });
  corners.erase(std::unique(corners.begin(), corners.end(), [](const Corner& a, const Corner& b) { return a.at == b.at; }),
                corners.end());
  if (corners.size() != static_cast<size_t>(num_owned_) * bs)
    throw std::logic_error("fragment tables: an output block vertex without a last-level point");
  for (const Corner& c : corners) {
    add_limit_position(last, c.v, lim);
    add_limit_tangents(last, c.v, side_of(last, c.v, c.face), c.face, lim);
    lim.at_control_vertex.push_back(control[c.v]);
  }
  t.owned_faces = num_owned_;
}

// Which of a vertex's sides face f lies on: for a corner the face's slot in the ring (-1 - slot);
// for an interior crease the ring rotation that puts f between the leading and trailing crease
// edges; 0 for everything else.
template <Sdc::SchemeType S>
int TableBuilder<S>::side_of(const Far::TopologyLevel& last, int v, int f) const {
  const Sdc::Crease::Rule rule = last.GetVertexRule(v);
  Far::ConstIndexArray vf = last.GetVertexFaces(v), ve = last.GetVertexEdges(v);
  int slot = 0;
  while (vf[slot] != f) ++slot;
  if (rule == Sdc::Crease::RULE_CORNER) return -1 - slot;
  if (rule != Sdc::Crease::RULE_CREASE || last.IsVertexBoundary(v)) return 0;
  int sharp[2] = {-1, -1};
  for (int i = 0, k = 0; i < ve.size() && k < 2; ++i)
    if (last.GetEdgeSharpness(ve[i]) > 0) sharp[k++] = i;
  return slot >= sharp[0] && slot < sharp[1] ? 0 : sharp[1];
}

template <Sdc::SchemeType S>
std::vector<uint32_t> TableBuilder<S>::ring_vertices(const Far::TopologyLevel& last, int v, int start) const {
  Far::ConstIndexArray ve = last.GetVertexEdges(v);
  std::vector<uint32_t> out;
  for (int i = 0; i < ve.size(); ++i) {
    Far::ConstIndexArray ends = last.GetEdgeVertices(ve[(i + start) % ve.size()]);
    out.push_back(parent_slot(ends[0] == v ? ends[1] : ends[0]));
  }
  return out;
}

template <Sdc::SchemeType S>
std::vector<uint32_t> TableBuilder<S>::opposite_vertices(const Far::TopologyLevel& last, int v, int start) const {
  Far::ConstIndexArray vf = last.GetVertexFaces(v);
  Far::ConstLocalIndexArray in_face = last.GetVertexFaceLocalIndices(v);
  std::vector<uint32_t> out;
  for (int i = 0; i < vf.size(); ++i) {
    const int k = (i + start) % vf.size();
    Far::ConstIndexArray fv = last.GetFaceVertices(vf[k]);
    out.push_back(parent_slot(fv[(in_face[k] + 2) % fv.size()]));
  }
  return out;
}

template <Sdc::SchemeType S>
std::vector<float> TableBuilder<S>::weights(int count, const float& (Mask::*at)(int) const, const Mask& m) {
  std::vector<float> w(count);
  for (int i = 0; i < count; ++i) w[i] = (m.*at)(i);
  return w;
}

// A dart's limit, or a smooth valence-2 vertex's, from the eigenvector of its ring's matrix
// (ring_limit.h): a dart's ring starts at its sharp edge, the same in every fragment.
template <Sdc::SchemeType S>
bool TableBuilder<S>::add_exact_limit_position(const Far::TopologyLevel& last, int v, LimitTable& lim) const {
  const Sdc::Crease::Rule rule = last.GetVertexRule(v);
  Far::ConstIndexArray ve = last.GetVertexEdges(v);
  if (last.IsVertexBoundary(v) || last.IsVertexSemiSharp(v)) return false;
  int sharp = -1;
  for (int i = 0; i < ve.size(); ++i) {
    if (last.IsEdgeSemiSharp(ve[i])) return false;
    if (last.GetEdgeSharpness(ve[i]) > 0) sharp = i;
  }
  const bool dart = rule == Sdc::Crease::RULE_DART && sharp >= 0 && last.IsEdgeInfSharp(ve[sharp]);
  const bool valence2 = rule == Sdc::Crease::RULE_SMOOTH && ve.size() == 2;
  if (!dart && !valence2) return false;
  const std::vector<double> w = ring_limit_weights(last, refiner_->GetSchemeOptions(), kCatmark, v, dart ? sharp : 0);
  const int n = ve.size();
  const std::vector<uint32_t> eref = ring_vertices(last, v, dart ? sharp : 0), fref = opposite_vertices(last, v, dart ? sharp : 0);
  if (valence2) {  // symmetric under the ring's rotation: the uniform form
    std::vector<float> ew(n, float((w[1] + w[2]) / 2)), fw;
    if (kCatmark) fw.assign(n, float((w[3] + w[4]) / 2));
    lim.position.push_back(vertex_rule(parent_slot(v), float(w[0]), ew, eref, fw, kCatmark ? fref : std::vector<uint32_t>{},
                                       lim.ring, "limit"));
    lim.stencil.push_back(-1);
    return true;
  }
  lim.position.push_back({parent_slot(v), parent_slot(v), parent_slot(v), 0, 0, 0, 1, 0, 0, 0});  // centre for refined_points
  lim.stencil.push_back(static_cast<int32_t>(lim.stencil_begin.size()) - 1);
  lim.stencil_slot.push_back(parent_slot(v));
  for (int k = 0; k < n; ++k) lim.stencil_slot.push_back(eref[k]);
  if (kCatmark)
    for (int k = 0; k < n; ++k) lim.stencil_slot.push_back(fref[k]);
  for (double x : w) lim.stencil_w.push_back(static_cast<float>(x));
  lim.stencil_begin.push_back(static_cast<uint32_t>(lim.stencil_slot.size()));
  return true;
}

template <Sdc::SchemeType S>
void TableBuilder<S>::add_limit_position(const Far::TopologyLevel& last, int v, LimitTable& lim) const {
  if (add_exact_limit_position(last, v, lim)) return;
  lim.stencil.push_back(-1);
  const int max = std::max(last.GetVertexEdges(v).size(), last.GetVertexFaces(v).size()) + 1;
  Mask pos(max);
  scheme_.ComputeVertexLimitMask(VertexHood(last, last, v, v), pos, last.GetVertexRule(v));
  const std::vector<uint32_t> eref = ring_vertices(last, v, 0), fref = opposite_vertices(last, v, 0);
  const std::vector<float> ew = weights(pos.GetNumEdgeWeights(), &Mask::EdgeWeight, pos);
  const std::vector<float> fw = weights(pos.GetNumFaceWeights(), &Mask::FaceWeight, pos);
  lim.position.push_back(vertex_rule(parent_slot(v), pos.VertexWeight(0), ew, {eref.begin(), eref.begin() + ew.size()},
                                     fw, {fref.begin(), fref.begin() + fw.size()}, lim.ring, "limit"));
}

// The ring's rules repeat from this level on: no sharpness left that decays.
template <Sdc::SchemeType S>
bool TableBuilder<S>::stationary(const Far::TopologyLevel& last, int v) const {
  if (last.IsVertexSemiSharp(v)) return false;
  for (int e : last.GetVertexEdges(v))
    if (last.IsEdgeSemiSharp(e)) return false;
  return true;
}

// Where Far's tangents are not exact, the ring's eigenvectors on the side of `face` (ring_limit.h).
template <Sdc::SchemeType S>
bool TableBuilder<S>::add_exact_limit_tangents(const Far::TopologyLevel& last, int v, int face,
                                                std::map<uint32_t, std::pair<float, float>>& tangent) const {
  if (far_tangent_masks_exact(last, v, rule_) || !stationary(last, v)) return false;
  Far::ConstIndexArray vf = last.GetVertexFaces(v);
  const int slot = static_cast<int>(std::find(vf.begin(), vf.end(), face) - vf.begin());
  const RingTangents t = ring_limit_tangents(last, refiner_->GetSchemeOptions(), kCatmark, v, slot);
  if (t.first.empty()) return false;
  std::vector<uint32_t> ring = {parent_slot(v)};
  for (uint32_t r : ring_vertices(last, v, 0)) ring.push_back(r);
  if (kCatmark)
    for (uint32_t r : opposite_vertices(last, v, 0)) ring.push_back(r);
  for (size_t k = 0; k < ring.size(); ++k) {
    auto& [a, b] = tangent[ring[k]];
    a += static_cast<float>(t.first[k]), b += static_cast<float>(t.second[k]);
  }
  return true;
}

template <Sdc::SchemeType S>
void TableBuilder<S>::add_limit_tangents(const Far::TopologyLevel& last, int v, int side, int face,
                                         LimitTable& lim) const {
  std::map<uint32_t, std::pair<float, float>> tangent;
  auto add = [&](uint32_t slot, float w1, float w2) {
    auto& [a, b] = tangent[slot];
    a += w1, b += w2;
  };
  const bool exact = add_exact_limit_tangents(last, v, face, tangent);
  if (!exact && side < 0) {  // a corner: the two edges bounding the face (Sdc's corner tangents, per face)
    const std::vector<uint32_t> eref = ring_vertices(last, v, 0);
    const int slot = -1 - side;
    add(parent_slot(v), -1, -1);
    add(eref[slot], 1, 0);
    add(eref[(slot + 1) % eref.size()], 0, 1);
  } else if (!exact) {
    const int max = std::max(last.GetVertexEdges(v).size(), last.GetVertexFaces(v).size()) + 1;
    Mask pos(max), t1(max), t2(max);
    scheme_.ComputeVertexLimitMask(VertexHood(last, last, v, v, side), pos, t1, t2, last.GetVertexRule(v));
    const std::vector<uint32_t> eref = ring_vertices(last, v, side), fref = opposite_vertices(last, v, side);
    if (add_regular_tangents(last, v, t1, t2, eref, fref, lim)) return;
    add(parent_slot(v), t1.VertexWeight(0), t2.VertexWeight(0));
    for (int i = 0; i < t1.GetNumEdgeWeights(); ++i) add(eref[i], t1.EdgeWeight(i), t2.EdgeWeight(i));
    for (int i = 0; i < t1.GetNumFaceWeights(); ++i) add(fref[i], t1.FaceWeight(i), t2.FaceWeight(i));
  }
  lim.regular.push_back(-1);
  for (const auto& [slot, w] : tangent) {
    lim.tangent_slot.push_back(slot);
    lim.tangent_w1.push_back(w.first);
    lim.tangent_w2.push_back(w.second);
  }
  lim.tangent_begin.push_back(static_cast<uint32_t>(lim.tangent_slot.size()));
}

// The regular vertex's tangents, in Sdc's order (centre, ring, opposite vertices); false where
// the vertex is not regular or its weights differ from the first regular vertex's.
template <Sdc::SchemeType S>
bool TableBuilder<S>::add_regular_tangents(const Far::TopologyLevel& last, int v, const Mask& t1, const Mask& t2,
                          const std::vector<uint32_t>& eref, const std::vector<uint32_t>& fref, LimitTable& lim) const {
  const int valence = kCatmark ? 4 : 6;
  if (last.GetVertexRule(v) != Sdc::Crease::RULE_SMOOTH || last.IsVertexBoundary(v) ||
      last.GetVertexEdges(v).size() != valence || t1.GetNumEdgeWeights() != valence ||
      t1.GetNumFaceWeights() != (kCatmark ? 4 : 0))
    return false;
  std::vector<float> w1 = {t1.VertexWeight(0)}, w2 = {t2.VertexWeight(0)};
  std::vector<uint32_t> slots = {parent_slot(v)};
  for (int i = 0; i < valence; ++i) w1.push_back(t1.EdgeWeight(i)), w2.push_back(t2.EdgeWeight(i)), slots.push_back(eref[i]);
  for (int i = 0; i < t1.GetNumFaceWeights(); ++i)
    w1.push_back(t1.FaceWeight(i)), w2.push_back(t2.FaceWeight(i)), slots.push_back(fref[i]);
  // The weights kernel.cpp's regular_normal() is written for.
  auto near = [](const std::vector<float>& a, const std::vector<double>& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
      if (std::abs(a[i] - b[i]) > 1e-6) return false;
    return true;
  };
  const RegularTangents& regular = regular_tangents(kCatmark);
  if (!near(w1, regular.first) || !near(w2, regular.second)) return false;
  lim.regular_size = static_cast<int>(slots.size());
  lim.regular.push_back(static_cast<int32_t>(lim.regular_slots.size() / lim.regular_size));
  lim.regular_slots.insert(lim.regular_slots.end(), slots.begin(), slots.end());
  lim.tangent_begin.push_back(lim.tangent_begin.back());
  return true;
}

template void TableBuilder<Sdc::SCHEME_CATMARK>::make_limit(ShapeTables&) const;
template void TableBuilder<Sdc::SCHEME_LOOP>::make_limit(ShapeTables&) const;

}  // namespace sdb::fragments::detail
