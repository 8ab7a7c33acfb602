#include "schemes/fragments/tables.h"

#include "schemes/fragments/table_builder.h"

namespace sdb::fragments {
namespace detail {

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


template <Sdc::SchemeType S>
ShapeTables TableBuilder<S>::build() {
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
  add_net_tangents(t, kCatmark);
  return t;
}

template <Sdc::SchemeType S>
std::vector<RegionFace> TableBuilder<S>::base_region() const {
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

template <Sdc::SchemeType S>
uint32_t TableBuilder<S>::parent_slot(int v) const {
  if (slot_[v] < 0) throw std::logic_error("fragment net lacks a point a pattern needs");
  return static_cast<uint32_t>(slot_[v]);
}

template <Sdc::SchemeType S>
std::vector<RegionFace> TableBuilder<S>::child_region(const Far::TopologyLevel& parent, const Far::TopologyLevel& child) const {
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
template <Sdc::SchemeType S>
std::vector<char> TableBuilder<S>::needed_vertices(const Far::TopologyLevel& level) const {
  std::vector<char> needed(level.GetNumVertices(), 0);
  for (const RegionFace& r : region_)
    for (int v : level.GetFaceVertices(r.face))
      for (int f : level.GetVertexFaces(v))
        for (int w : level.GetFaceVertices(f)) needed[w] = 1;
  return needed;
}

template <Sdc::SchemeType S>
LevelTable TableBuilder<S>::refine_level(int d) {
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

template <Sdc::SchemeType S>
FaceRule TableBuilder<S>::face_rule(const Far::TopologyLevel& parent, int f) const {
  Far::ConstIndexArray fv = parent.GetFaceVertices(f);
  if (fv.size() != 4) throw std::logic_error("Catmull-Clark fragments take quads only");
  return {parent_slot(fv[0]), parent_slot(fv[1]), parent_slot(fv[2]), parent_slot(fv[3])};
}

// For Catmull-Clark the face weights apply to the child face points (Far's face centres), for
// Loop to the vertex opposite the edge in each face, as PrimvarRefiner applies them.
template <Sdc::SchemeType S>
EdgeRule TableBuilder<S>::edge_rule(const Far::TopologyLevel& parent, const Far::TopologyLevel& child, int e,
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

template <Sdc::SchemeType S>
VertexRule TableBuilder<S>::vertex_rule_at(const Far::TopologyLevel& parent, const Far::TopologyLevel& child, int v,
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

template class TableBuilder<Sdc::SCHEME_CATMARK>;
template class TableBuilder<Sdc::SCHEME_LOOP>;

}  // namespace detail

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
  if (rule == SubdivisionRule::Loop) return detail::TableBuilder<OpenSubdiv::Sdc::SCHEME_LOOP>(net, rule, depth, out_depth).build();
  return detail::TableBuilder<OpenSubdiv::Sdc::SCHEME_CATMARK>(net, rule, depth, out_depth).build();
}

}  // namespace sdb::fragments
