#include "schemes/fragments/tables.h"

#include <opensubdiv/far/topologyRefiner.h>
#include <opensubdiv/sdc/catmarkScheme.h>
#include <opensubdiv/sdc/loopScheme.h>
#include <opensubdiv/sdc/scheme.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "harness/core/errors.h"
#include "harness/mesh/osd_topology.h"
#include "schemes/fragments/ring_limit.h"
#include "schemes/fragments/sdc_masks.h"

namespace sdb::fragments {
namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

// The kernel's ring sums take at most this many terms.
constexpr int kMaxValence = 1024;

[[noreturn]] void asymmetric(const char* what) {
  throw Unsupported(std::string("an OpenSubdiv ") + what +
                    " mask without the symmetric form the fragment kernel evaluates (README.md)");
}

// wv c + (weights on the ring) as wv c + wc (p0 + p1) + we sum(e) + wf sum(f). The crease pair is
// chosen from the weights alone, never from where the ring starts, so that every fragment meeting
// this vertex picks the same pair.
VertexRule vertex_rule(uint32_t centre, float wv, const std::vector<float>& ew, const std::vector<uint32_t>& eref,
                       const std::vector<float>& fw, const std::vector<uint32_t>& fref, std::vector<uint32_t>& ring,
                       const char* what) {
  if (eref.size() > kMaxValence || fref.size() > kMaxValence)
    throw Unsupported("a vertex of valence " + std::to_string(eref.size()) + ", past the fragment tables' " +
                      std::to_string(kMaxValence));
  VertexRule r{centre, centre, centre, static_cast<uint32_t>(ring.size()), 0, 0, wv, 0, 0, 0};
  std::map<float, int> groups;
  for (float w : ew) ++groups[w];
  int pair_a = -1, pair_b = -1;
  if (groups.size() == 1) {
    r.we = groups.begin()->first;
  } else if (groups.size() == 2) {
    auto lo = groups.begin(), hi = std::next(lo);
    auto pair = hi->second == 2 ? hi : lo->second == 2 ? lo : groups.end();
    if (pair == groups.end() || ew.size() < 3) asymmetric(what);
    const float rest = pair == hi ? lo->first : hi->first;
    r.we = rest;
    r.wc = pair->first - rest;
    for (size_t i = 0; i < ew.size(); ++i)
      if (ew[i] == pair->first) (pair_a < 0 ? pair_a : pair_b) = static_cast<int>(i);
    r.p0 = eref[pair_a], r.p1 = eref[pair_b];
  } else if (!groups.empty()) {
    asymmetric(what);
  }
  if (r.we != 0) {
    ring.insert(ring.end(), eref.begin(), eref.end());
    r.num_e = static_cast<uint16_t>(eref.size());
  }
  if (!fw.empty()) {
    if (std::any_of(fw.begin(), fw.end(), [&](float w) { return w != fw[0]; })) asymmetric(what);
    r.wf = fw[0];
    if (r.wf != 0) {
      ring.insert(ring.end(), fref.begin(), fref.end());
      r.num_f = static_cast<uint16_t>(fref.size());
    }
  }
  return r;
}

// A face of the owned region at some level: which owned face it lies in and its corners' ptex
// grid coordinates in units of 2^-depth.
struct RegionFace {
  int face, owner;
  std::array<std::array<int, 2>, 4> uv;
};

template <Sdc::SchemeType S>
class TableBuilder {
 public:
  TableBuilder(const LocalNet& net, SubdivisionRule rule, int depth, int out_depth)
      : rule_(rule), depth_(depth), out_depth_(out_depth), refiner_(make_refiner(net.mesh, rule)),
        num_owned_(net.num_owned) {
    Far::TopologyRefiner::UniformOptions options(depth);
    options.fullTopologyInLastLevel = true;
    refiner_->RefineUniform(options);
    scheme_ = Sdc::Scheme<S>(refiner_->GetSchemeOptions());
  }

  ShapeTables build() {
    ShapeTables t;
    t.depth = depth_;
    const Far::TopologyLevel& l0 = refiner_->GetLevel(0);
    t.num_slots0 = l0.GetNumVertices();
    t.max_slots = t.num_slots0;
    slot_.resize(l0.GetNumVertices());
    for (int v = 0; v < l0.GetNumVertices(); ++v) slot_[v] = v;
    region_ = base_region();
    for (int d = 1; d <= depth_; ++d) {
      t.levels.push_back(refine_level(d));
      t.max_slots = std::max(t.max_slots, t.levels.back().num_slots);
    }
    make_limit(t);
    return t;
  }

 private:
  static constexpr bool kCatmark = S == Sdc::SCHEME_CATMARK;

  std::vector<RegionFace> base_region() const {
    const int s = 1 << depth_;
    std::vector<RegionFace> region;
    for (int f = 0; f < num_owned_; ++f) {
      RegionFace r{f, f, {}};
      if (kCatmark) r.uv = {{{0, 0}, {s, 0}, {s, s}, {0, s}}};
      else r.uv = {{{0, 0}, {s, 0}, {0, s}, {0, 0}}};
      region.push_back(r);
    }
    return region;
  }

  uint32_t parent_slot(int v) const {
    if (slot_[v] < 0) throw std::logic_error("fragment net lacks a point a pattern needs");
    return static_cast<uint32_t>(slot_[v]);
  }

  std::vector<RegionFace> child_region(const Far::TopologyLevel& parent, const Far::TopologyLevel& child) const {
    std::vector<RegionFace> out;
    for (const RegionFace& r : region_) {
      Far::ConstIndexArray fv = parent.GetFaceVertices(r.face), fe = parent.GetFaceEdges(r.face);
      const int n = fv.size();
      std::array<int, 2> centre{0, 0};
      for (int k = 0; k < n; ++k) centre[0] += r.uv[k][0], centre[1] += r.uv[k][1];
      centre = {centre[0] / n, centre[1] / n};  // exact: corners lie 2^(depth - d) apart
      const int face_child = kCatmark ? parent.GetFaceChildVertex(r.face) : -1;
      for (int c : parent.GetFaceChildFaces(r.face)) {
        RegionFace cr{c, r.owner, {}};
        Far::ConstIndexArray cv = child.GetFaceVertices(c);
        for (int j = 0; j < cv.size(); ++j) {
          if (cv[j] == face_child) cr.uv[j] = centre;
          for (int k = 0; k < n; ++k) {
            if (cv[j] == parent.GetVertexChildVertex(fv[k])) cr.uv[j] = r.uv[k];
            if (cv[j] == parent.GetEdgeChildVertex(fe[k]))
              cr.uv[j] = {(r.uv[k][0] + r.uv[(k + 1) % n][0]) / 2, (r.uv[k][1] + r.uv[(k + 1) % n][1]) / 2};
          }
        }
        out.push_back(cr);
      }
    }
    return out;
  }

  // The points of level d a fragment keeps: its region's vertices and every vertex of a face
  // touching one of them.
  std::vector<char> needed_vertices(const Far::TopologyLevel& level) const {
    std::vector<char> needed(level.GetNumVertices(), 0);
    for (const RegionFace& r : region_)
      for (int v : level.GetFaceVertices(r.face))
        for (int f : level.GetVertexFaces(v))
          for (int w : level.GetFaceVertices(f)) needed[w] = 1;
    return needed;
  }

  LevelTable refine_level(int d) {
    const Far::TopologyLevel& parent = refiner_->GetLevel(d - 1);
    const Far::TopologyLevel& child = refiner_->GetLevel(d);
    region_ = child_region(parent, child);
    const std::vector<char> needed = needed_vertices(child);
    std::vector<int> child_slot(child.GetNumVertices(), -1);
    LevelTable t;
    uint32_t next = 0;
    auto take = [&](int c) { return c >= 0 && needed[c] && child_slot[c] < 0 ? (child_slot[c] = next++, true) : false; };
    if (kCatmark)
      for (int f = 0; f < parent.GetNumFaces(); ++f)
        if (take(parent.GetFaceChildVertex(f))) t.faces.push_back(face_rule(parent, f));
    for (int e = 0; e < parent.GetNumEdges(); ++e)
      if (take(parent.GetEdgeChildVertex(e))) t.edges.push_back(edge_rule(parent, child, e, child_slot));
    for (int v = 0; v < parent.GetNumVertices(); ++v)
      if (take(parent.GetVertexChildVertex(v))) t.vertices.push_back(vertex_rule_at(parent, child, v, child_slot, t.ring));
    t.num_slots = next;
    for (int c = 0; c < child.GetNumVertices(); ++c)
      if (needed[c] && child_slot[c] < 0) throw std::logic_error("fragment point without a parent");
    slot_ = std::move(child_slot);
    return t;
  }

  FaceRule face_rule(const Far::TopologyLevel& parent, int f) const {
    Far::ConstIndexArray fv = parent.GetFaceVertices(f);
    if (fv.size() != 4) throw std::logic_error("Catmull-Clark fragments take quads only");
    return {parent_slot(fv[0]), parent_slot(fv[1]), parent_slot(fv[2]), parent_slot(fv[3])};
  }

  // For Catmull-Clark the face weights apply to the child face points (Far's face centres), for
  // Loop to the vertex opposite the edge in each face, as PrimvarRefiner applies them.
  EdgeRule edge_rule(const Far::TopologyLevel& parent, const Far::TopologyLevel& child, int e,
                     const std::vector<int>& child_slot) const {
    Far::ConstIndexArray ev = parent.GetEdgeVertices(e), ef = parent.GetEdgeFaces(e);
    Mask mask(std::max(2, ef.size()));
    const int c = parent.GetEdgeChildVertex(e);
    const Sdc::Crease::Rule p_rule = parent.GetEdgeSharpness(e) > 0 ? Sdc::Crease::RULE_CREASE : Sdc::Crease::RULE_SMOOTH;
    scheme_.ComputeEdgeVertexMask(EdgeHood(parent, e), mask, p_rule, child.GetVertexRule(c));
    if (mask.VertexWeight(0) != mask.VertexWeight(1)) asymmetric("edge");
    EdgeRule r{parent_slot(ev[0]), parent_slot(ev[1]), parent_slot(ev[0]), parent_slot(ev[1]), mask.VertexWeight(0), 0};
    if (mask.GetNumFaceWeights() == 0) return r;
    if (ef.size() != 2 || mask.FaceWeight(0) != mask.FaceWeight(1)) asymmetric("edge");
    r.wf = mask.FaceWeight(0);
    uint32_t f[2];
    for (int i = 0; i < 2; ++i) {
      if (mask.AreFaceWeightsForFaceCenters()) {
        const int fc = parent.GetFaceChildVertex(ef[i]);
        if (child_slot[fc] < 0) throw std::logic_error("edge point before its face point");
        f[i] = static_cast<uint32_t>(child_slot[fc]);
      } else {
        Far::ConstIndexArray fe = parent.GetFaceEdges(ef[i]), fv = parent.GetFaceVertices(ef[i]);
        int k = 0;
        while (fe[k] != e) ++k;
        f[i] = parent_slot(fv[(k + 2) % fv.size()]);
      }
    }
    r.f0 = f[0], r.f1 = f[1];
    return r;
  }

  VertexRule vertex_rule_at(const Far::TopologyLevel& parent, const Far::TopologyLevel& child, int v,
                            const std::vector<int>& child_slot, std::vector<uint32_t>& ring) const {
    Far::ConstIndexArray ve = parent.GetVertexEdges(v), vf = parent.GetVertexFaces(v);
    Mask mask(std::max(ve.size(), vf.size()) + 1);
    const int c = parent.GetVertexChildVertex(v);
    scheme_.ComputeVertexVertexMask(VertexHood(parent, child, v, c), mask, parent.GetVertexRule(v), child.GetVertexRule(c));
    std::vector<float> ew(mask.GetNumEdgeWeights()), fw(mask.GetNumFaceWeights());
    std::vector<uint32_t> eref, fref;
    for (int i = 0; i < mask.GetNumEdgeWeights(); ++i) {
      Far::ConstIndexArray ends = parent.GetEdgeVertices(ve[i]);
      ew[i] = mask.EdgeWeight(i);
      eref.push_back(parent_slot(ends[0] == v ? ends[1] : ends[0]));
    }
    for (int i = 0; i < mask.GetNumFaceWeights(); ++i) {
      if (!mask.AreFaceWeightsForFaceCenters()) asymmetric("vertex");
      fw[i] = mask.FaceWeight(i);
      fref.push_back(static_cast<uint32_t>(child_slot[parent.GetFaceChildVertex(vf[i])]));
    }
    return vertex_rule(parent_slot(v), mask.VertexWeight(0), ew, eref, fw, fref, ring, "vertex");
  }

  // Limit masks as PrimvarRefiner::Limit takes them: the last level's vertex rule, face weights
  // on the vertex opposite in each face. Positions are one per vertex; tangents one per vertex
  // and side: at a crease or corner the surface has a normal on each side, and each owned face
  // takes the one of its own side (Far's masks give the side the vertex's ring starts in).
  void make_limit(ShapeTables& t) const {
    const Far::TopologyLevel& last = refiner_->GetLevel(depth_);
    std::vector<int> entry(last.GetNumVertices(), -1);
    std::map<std::pair<int, int>, int> tangent_entry;
    const int bs = block_size(rule_, out_depth_), shift = depth_ - out_depth_, mask = (1 << shift) - 1;
    t.block.assign(static_cast<size_t>(num_owned_) * bs, 0);
    t.block_normal.assign(t.block.size(), 0);
    LimitTable& lim = t.limit;
    lim.tangent_begin.push_back(0);
    for (const RegionFace& r : region_) {
      Far::ConstIndexArray fv = last.GetFaceVertices(r.face);
      for (int j = 0; j < fv.size(); ++j) {
        const int v = fv[j];
        if ((r.uv[j][0] & mask) || (r.uv[j][1] & mask)) continue;  // between the output's grid points
        if (entry[v] < 0) {
          entry[v] = static_cast<int>(lim.position.size());
          add_limit_position(last, v, lim);
        }
        const int side = side_of(last, v, r.face);
        auto [it, fresh] = tangent_entry.try_emplace({v, side}, static_cast<int>(lim.regular.size()));
        if (fresh) add_limit_tangents(last, v, side, lim);
        const size_t at = static_cast<size_t>(r.owner) * bs +
                          block_index(rule_, out_depth_, r.uv[j][0] >> shift, r.uv[j][1] >> shift);
        t.block[at] = entry[v];
        t.block_normal[at] = it->second;
      }
    }
  }

  // Which of a vertex's sides face f lies on: for a corner the face's slot in the ring (-1 - slot);
  // for an interior crease the ring rotation that puts f between the leading and trailing crease
  // edges; 0 for everything else.
  int side_of(const Far::TopologyLevel& last, int v, int f) const {
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

  std::vector<uint32_t> ring_vertices(const Far::TopologyLevel& last, int v, int start) const {
    Far::ConstIndexArray ve = last.GetVertexEdges(v);
    std::vector<uint32_t> out;
    for (int i = 0; i < ve.size(); ++i) {
      Far::ConstIndexArray ends = last.GetEdgeVertices(ve[(i + start) % ve.size()]);
      out.push_back(parent_slot(ends[0] == v ? ends[1] : ends[0]));
    }
    return out;
  }

  std::vector<uint32_t> opposite_vertices(const Far::TopologyLevel& last, int v, int start) const {
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

  static std::vector<float> weights(int count, const float& (Mask::*at)(int) const, const Mask& m) {
    std::vector<float> w(count);
    for (int i = 0; i < count; ++i) w[i] = (m.*at)(i);
    return w;
  }

  // A dart's limit, or a smooth valence-2 vertex's, from the eigenvector of its ring's matrix
  // (ring_limit.h): a dart's ring starts at its sharp edge, the same in every fragment.
  bool add_exact_limit_position(const Far::TopologyLevel& last, int v, LimitTable& lim) const {
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

  void add_limit_position(const Far::TopologyLevel& last, int v, LimitTable& lim) const {
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

  void add_limit_tangents(const Far::TopologyLevel& last, int v, int side, LimitTable& lim) const {
    std::map<uint32_t, std::pair<float, float>> tangent;
    auto add = [&](uint32_t slot, float w1, float w2) {
      auto& [a, b] = tangent[slot];
      a += w1, b += w2;
    };
    if (side < 0) {  // a corner: the two edges bounding the face (Sdc's corner tangents, per face)
      const std::vector<uint32_t> eref = ring_vertices(last, v, 0);
      const int slot = -1 - side;
      add(parent_slot(v), -1, -1);
      add(eref[slot], 1, 0);
      add(eref[(slot + 1) % eref.size()], 0, 1);
    } else {
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
  bool add_regular_tangents(const Far::TopologyLevel& last, int v, const Mask& t1, const Mask& t2,
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
    const float h = 0.866025404f;
    static const std::vector<float> cc1 = {0, 4, 0, -4, 0, 1, -1, -1, 1}, cc2 = {0, 0, 4, 0, -4, 1, 1, -1, -1};
    static const std::vector<float> loop1 = {0, 1, 0.5f, -0.5f, -1, -0.5f, 0.5f}, loop2 = {0, 0, h, h, 0, -h, -h};
    auto near = [](const std::vector<float>& a, const std::vector<float>& b) {
      if (a.size() != b.size()) return false;
      for (size_t i = 0; i < a.size(); ++i)
        if (std::abs(a[i] - b[i]) > 1e-6f) return false;
      return true;
    };
    if (!(kCatmark ? near(w1, cc1) && near(w2, cc2) : near(w1, loop1) && near(w2, loop2))) return false;
    lim.regular_size = static_cast<int>(slots.size());
    lim.regular.push_back(static_cast<int32_t>(lim.regular_slots.size() / lim.regular_size));
    lim.regular_slots.insert(lim.regular_slots.end(), slots.begin(), slots.end());
    lim.tangent_begin.push_back(lim.tangent_begin.back());
    return true;
  }

  SubdivisionRule rule_;
  int depth_, out_depth_;
  std::unique_ptr<Far::TopologyRefiner> refiner_;
  int num_owned_;
  Sdc::Scheme<S> scheme_;
  std::vector<int> slot_;  // local vertex of the current level -> slot, or -1
  std::vector<RegionFace> region_;
};

}  // namespace

int block_size(SubdivisionRule rule, int depth) {
  const int n = (1 << depth) + 1;
  return rule == SubdivisionRule::Loop ? n * (n + 1) / 2 : n * n;
}

int block_index(SubdivisionRule rule, int depth, int i, int j) {
  const int n = (1 << depth) + 1;
  return rule == SubdivisionRule::Loop ? j * n - j * (j - 1) / 2 + i : j * n + i;
}

std::vector<uint32_t> block_triangles(SubdivisionRule rule, int depth) {
  const int s = 1 << depth;
  std::vector<uint32_t> t;
  auto at = [&](int i, int j) { return static_cast<uint32_t>(block_index(rule, depth, i, j)); };
  for (int j = 0; j < s; ++j)
    for (int i = 0; i < s; ++i) {
      if (rule == SubdivisionRule::Loop) {
        if (i + j >= s) continue;
        t.insert(t.end(), {at(i, j), at(i + 1, j), at(i, j + 1)});
        if (i + j + 1 < s) t.insert(t.end(), {at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      } else {
        t.insert(t.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      }
    }
  return t;
}

ShapeTables build_tables(const LocalNet& net, SubdivisionRule rule, int depth, int out_depth) {
  if (out_depth < 0) out_depth = depth;
  if (rule == SubdivisionRule::Loop) return TableBuilder<Sdc::SCHEME_LOOP>(net, rule, depth, out_depth).build();
  return TableBuilder<Sdc::SCHEME_CATMARK>(net, rule, depth, out_depth).build();
}

}  // namespace sdb::fragments
