#include "schemes/mipgh/shader.h"

#include <opensubdiv/sdc/catmarkScheme.h>
#include <opensubdiv/sdc/loopScheme.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <optional>

#include "harness/mesh/osd_topology.h"
#include "harness/mesh/sdc_mask.h"
#include "harness/reference/local_mesh.h"
#include "harness/reference/ring_limit.h"
#include "harness/reference/vertex_limit.h"

namespace sdb::mipgh {

namespace Sdc = OpenSubdiv::Sdc;
namespace Far = OpenSubdiv::Far;


void VertexDisk::resize(int num_edges, int num_faces) {
  edges = num_edges, faces = num_faces, sided = false;
  if (e.size() < size_t(num_edges)) e.resize(num_edges), edge_sharpness.resize(num_edges), child_edge_sharpness.resize(num_edges);
  if (d.size() < size_t(num_faces)) d.resize(num_faces), face_size.resize(num_faces);
}

bool VertexDisk::smooth() const {
  if (sharpness > 0 || child_sharpness > 0 || edges != faces) return false;
  for (int i = 0; i < edges; ++i)
    if (edge_sharpness[i] > 0) return false;
  return true;
}

namespace {

// The neighbourhood interfaces Sdc's mask queries read (what Far's Vtr gives PrimvarRefiner).
class SdcVertex {
 public:
  explicit SdcVertex(const VertexDisk& d) : d_(d) {}
  int GetNumEdges() const { return d_.edges; }
  int GetNumFaces() const { return d_.faces; }
  float GetSharpness() const { return d_.sharpness; }
  float* GetSharpnessPerEdge(float s[]) const {
    for (int i = 0; i < d_.edges; ++i) s[i] = d_.edge_sharpness[i];
    return s;
  }
  float GetChildSharpness(const Sdc::Crease&) const { return d_.child_sharpness; }
  float* GetChildSharpnessPerEdge(const Sdc::Crease&, float s[]) const {
    for (int i = 0; i < d_.edges; ++i) s[i] = d_.child_edge_sharpness[i];
    return s;
  }

 private:
  const VertexDisk& d_;
};

class SdcEdge {
 public:
  SdcEdge(const EdgeDisk& d, int facet_size) : d_(d), size_(facet_size) {}
  int GetNumFaces() const { return d_.faces; }
  float GetSharpness() const { return d_.sharpness; }
  void GetChildSharpnesses(const Sdc::Crease&, float s[2]) const { s[0] = d_.child_sharpness[0], s[1] = d_.child_sharpness[1]; }
  void GetNumVerticesPerFace(int counts[]) const { counts[0] = counts[1] = size_; }

 private:
  const EdgeDisk& d_;
  int size_;
};

template <class Disk>
V3 apply(const SdcMask& m, const Disk& d) {
  DoubleSum r;
  for_each_term(m, d, [&](V3 p, float w) { r.add(w, p); });
  return r.get();
}

// A tangent mask's weights sum to zero: applied to the points relative to the centre, the
// rounding of its float weights is not multiplied by the centre's distance from the origin (an
// eigenvector's tangents at a corner of one face weigh up to 1e3: 0.023 degrees on
// catmark_single_crease's corners, applied to the points themselves).
V3 apply_relative(const SdcMask& m, const VertexDisk& d) {
  DoubleSum r;
  for_each_term(m, d, [&](V3 p, float w) { r.add(w, p - d.c); });
  return r.get();
}

thread_local SdcMask t_pos, t_tan1, t_tan2;

}  // namespace

V3 catmark_vertex_smooth(const VertexDisk& disk) {
  const float n = static_cast<float>(disk.edges);
  const float w = 4 * n * n, cw = w - 7 * n;
  V3 es{0, 0, 0}, ds{0, 0, 0};
  for (int i = 0; i < disk.edges; ++i) es = es + disk.e[i], ds = ds + disk.d[i];
  return (cw / w) * disk.c + (6 / w) * es + (1 / w) * ds;
}

namespace {

// Sdc's limit masks are the limit at smooth vertices of valence 3 and more, regular creases and
// corners of one face; elsewhere (darts, valence 2, cone points, creases and corners of other
// valences) the exact ones come from the eigenvectors of the ring's subdivision matrix
// (harness/reference/ring_limit.h), on the side of a D-vertex disk's first face, whose D-facet
// names the node's SurfaceCoord (primitives.cpp), as they are at its creases and corners. Computed once per kind of disk: a ring of its own, made
// from the disk's valence, face sizes and tags (the rules repeat there: limit_depth_for).
class ExactLimitMasks {
 public:
  ExactLimitMasks(const Sdc::Options& options, SubdivisionRule rule) : options_(options), rule_(rule) {}

  void replace(const VertexDisk& disk, SdcMask& position, SdcMask& t1, SdcMask& t2) const {
    std::vector<float> key = {float(disk.edges), float(disk.faces), disk.sharpness, float(disk.sided)};
    for (int i = 0; i < disk.faces; ++i) key.push_back(disk.face_size[i]);
    for (int i = 0; i < disk.edges; ++i) key.push_back(disk.edge_sharpness[i]);
    std::shared_ptr<const Entry> entry;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      auto& slot = cache_[key];
      if (!slot) slot = std::make_shared<const Entry>(make(disk));
      entry = slot;
    }
    if (entry->position) position = *entry->position;
    if (entry->tangents) t1 = entry->tangents->first, t2 = entry->tangents->second;
  }

 private:
  struct Entry {
    std::optional<SdcMask> position;
    std::optional<std::pair<SdcMask, SdcMask>> tangents;
  };

  // Weights on ring_limit_vertices' order as a mask on the disk: the centre is vertex 0, edge i's
  // far end 1 + i, face i's opposite corner 1 + edges + i.
  static SdcMask mask_of(const std::vector<double>& w, const std::vector<int>& order, const VertexDisk& disk,
                         bool catmark) {
    SdcMask m(disk.edges + 1);
    m.SetNumVertexWeights(1);
    m.SetNumEdgeWeights(disk.edges);
    m.SetNumFaceWeights(catmark ? disk.faces : 0);
    m.SetFaceWeightsForFaceCenters(false);
    m.VertexWeight(0) = 0;
    for (int i = 0; i < disk.edges; ++i) m.EdgeWeight(i) = 0;
    for (int i = 0; catmark && i < disk.faces; ++i) m.FaceWeight(i) = 0;
    for (size_t k = 0; k < w.size(); ++k) {
      const int v = order[k];
      if (v == 0) m.VertexWeight(0) += float(w[k]);
      else if (v <= disk.edges) m.EdgeWeight(v - 1) += float(w[k]);
      else m.FaceWeight(v - 1 - disk.edges) += float(w[k]);
    }
    return m;
  }

  Entry make(const VertexDisk& disk) const {
    const bool catmark = rule_ == SubdivisionRule::CatmullClark;
    if (catmark)
      for (int i = 0; i < disk.faces; ++i)
        if (disk.face_size[i] != 4) return {};
    const auto refiner =
        refiner_of(ring_mesh(disk.edges, disk.faces, disk.edge_sharpness, disk.sharpness, catmark), rule_, options_);
    const Far::TopologyLevel& l = refiner->GetLevel(0);
    Entry out;
    if (l.IsVertexNonManifold(0) || vertex_sharpness_decays(l, 0)) return out;
    Far::ConstIndexArray ve = l.GetVertexEdges(0), vf = l.GetVertexFaces(0);
    int sharp = -1;
    for (int i = 0; i < ve.size(); ++i)
      if (l.GetEdgeSharpness(ve[i]) > 0) sharp = i;
    const Sdc::Crease::Rule rule = l.GetVertexRule(0);
    const bool dart = rule == Sdc::Crease::RULE_DART && !l.IsVertexBoundary(0);
    const bool valence2 = rule == Sdc::Crease::RULE_SMOOTH && !l.IsVertexBoundary(0) && ve.size() == 2;
    if (dart || valence2) {
      const int start = dart ? sharp : 0;
      out.position = mask_of(ring_limit_weights(l, options_, catmark, 0, start), ring_limit_vertices(l, 0, catmark, start),
                             disk, catmark);
    }
    // Sdc's crease and corner tangents are those of the side the ring starts in: a D-vertex's
    // first face's side is asked for (catmark_single_crease: 136 degrees from the other side).
    // Only where the faces around it have several sides: sharp edges between them, or a corner.
    int inner_sharp = 0;
    for (int e : ve) inner_sharp += l.GetEdgeSharpness(e) > 0 && l.GetEdgeFaces(e).size() == 2;
    const bool boundary = l.IsVertexBoundary(0), corner = l.GetVertexSharpness(0) > 0 && vf.size() > 1;
    const bool sided = disk.sided && (inner_sharp >= 2 || (boundary && inner_sharp >= 1) || corner);
    if (sided && disk.edge_sharpness[0] >= 10 && disk.edge_sharpness[1 % disk.edges] >= 10) {
      // The first face between two infinitely sharp edges: the ends of two crease curves, whose
      // directions are its side's tangents (an eigenvector's Jordan block approaches them only
      // as 1/K: 0.023 degrees on catmark_single_crease).
      std::vector<double> a(1 + disk.edges + (catmark ? disk.faces : 0), 0.0), b = a;
      std::vector<int> order(a.size());
      for (size_t k = 0; k < order.size(); ++k) order[k] = int(k);
      a[0] = b[0] = -1, a[1] = 1, b[1 + 1 % disk.edges] = 1;
      out.tangents = std::make_pair(mask_of(a, order, disk, catmark), mask_of(b, order, disk, catmark));
    } else if (sided || !far_tangent_masks_exact(l, 0, rule_)) {
      const int side = static_cast<int>(std::find(vf.begin(), vf.end(), 0) - vf.begin());
      const RingTangents t = ring_limit_tangents(l, options_, catmark, 0, side);
      const std::vector<int> order = ring_limit_vertices(l, 0, catmark, 0);
      // Scaled to weights of 1 at most: a Jordan block's come out as large as 1e4, and in float
      // applied to float points they cancel (0.023 degrees on catmark_single_crease's corners).
      auto scaled = [](std::vector<double> w) {
        double big = 0;
        for (double x : w) big = std::max(big, std::abs(x));
        for (double& x : w) x /= big > 0 ? big : 1;
        return w;
      };
      if (!t.first.empty())
        out.tangents = std::make_pair(mask_of(scaled(t.first), order, disk, catmark), mask_of(scaled(t.second), order, disk, catmark));
    }
    return out;
  }

  Sdc::Options options_;
  SubdivisionRule rule_;
  mutable std::mutex mutex_;
  mutable std::map<std::vector<float>, std::shared_ptr<const Entry>> cache_;
};

template <Sdc::SchemeType kType>
class SdcShader final : public MeshShader {
 public:
  explicit SdcShader(const Sdc::Options& options) : options_(options) {}

  V3 vertex_vertex(const VertexDisk& disk) const override {
    if (kType == Sdc::SCHEME_CATMARK && disk.smooth()) return catmark_vertex_smooth(disk);
    vertex_mask(disk, t_pos);
    return apply(t_pos, disk);
  }

  V3 edge_vertex(const EdgeDisk& disk) const override {
    edge_mask(disk, t_pos);
    return apply(t_pos, disk);
  }

  void limit(const VertexDisk& disk, V3& position, V3& normal) const override {
    limit_masks(disk, t_pos, t_tan1, t_tan2);
    position = apply(t_pos, disk);
    normal = normalized(cross(apply_relative(t_tan1, disk), apply_relative(t_tan2, disk)));
  }

  void vertex_mask(const VertexDisk& disk, SdcMask& mask) const override {
    Sdc::Scheme<kType>(options_).ComputeVertexVertexMask(SdcVertex(disk), mask);
  }

  void edge_mask(const EdgeDisk& disk, SdcMask& mask) const override {
    Sdc::Scheme<kType>(options_).ComputeEdgeVertexMask(SdcEdge(disk, kType == Sdc::SCHEME_CATMARK ? 4 : 3), mask);
  }

  void limit_masks(const VertexDisk& disk, SdcMask& position, SdcMask& t1, SdcMask& t2) const override {
    const Sdc::Crease crease(options_);
    const Sdc::Crease::Rule rule = crease.DetermineVertexVertexRule(disk.sharpness, disk.edges, disk.edge_sharpness.data());
    Sdc::Scheme<kType>(options_).ComputeVertexLimitMask(SdcVertex(disk), position, t1, t2, rule);
    if (!disk.smooth() || disk.edges < 3) exact_.replace(disk, position, t1, t2);
  }

 private:
  Sdc::Options options_;
  ExactLimitMasks exact_{options_, kType == Sdc::SCHEME_CATMARK ? SubdivisionRule::CatmullClark : SubdivisionRule::Loop};
};

}  // namespace

std::unique_ptr<MeshShader> make_shader(MeshRule rule, const Sdc::Options& options) {
  if (rule == MeshRule::QuadTri) return make_quad_tri_shader(options);
  if (rule == MeshRule::Loop) return std::make_unique<SdcShader<Sdc::SCHEME_LOOP>>(options);
  return std::make_unique<SdcShader<Sdc::SCHEME_CATMARK>>(options);
}

}  // namespace sdb::mipgh
