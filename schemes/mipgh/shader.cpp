#include "schemes/mipgh/shader.h"

#include <opensubdiv/sdc/catmarkScheme.h>
#include <opensubdiv/sdc/loopScheme.h>

#include <cmath>

#include "harness/mesh/sdc_mask.h"

namespace sdb::mipgh {

namespace Sdc = OpenSubdiv::Sdc;


void VertexDisk::resize(int num_edges, int num_faces) {
  edges = num_edges, faces = num_faces;
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
    normal = normalized(cross(apply(t_tan1, disk), apply(t_tan2, disk)));
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
  }

 private:
  Sdc::Options options_;
};

}  // namespace

std::unique_ptr<MeshShader> make_shader(MeshRule rule, const Sdc::Options& options) {
  if (rule == MeshRule::QuadTri) return make_quad_tri_shader(options);
  if (rule == MeshRule::Loop) return std::make_unique<SdcShader<Sdc::SCHEME_LOOP>>(options);
  return std::make_unique<SdcShader<Sdc::SCHEME_CATMARK>>(options);
}

}  // namespace sdb::mipgh
