#include "schemes/mipgh/shader.h"

#include <opensubdiv/sdc/catmarkScheme.h>
#include <opensubdiv/sdc/loopScheme.h>

#include <cmath>

namespace sdb::mipgh {

namespace Sdc = OpenSubdiv::Sdc;


void VertexDisk::resize(int num_edges, int num_faces) {
  edges = num_edges, faces = num_faces;
  if (e.size() < size_t(num_edges)) e.resize(num_edges), edge_sharpness.resize(num_edges), child_edge_sharpness.resize(num_edges);
  if (d.size() < size_t(num_faces)) d.resize(num_faces);
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

struct Sum {
  double x = 0, y = 0, z = 0;
  void add(double w, V3 p) { x += w * p.x, y += w * p.y, z += w * p.z; }
  V3 get() const { return {float(x), float(y), float(z)}; }
};

class Mask {
 public:
  using Weight = float;
  int GetNumVertexWeights() const { return nv_; }
  int GetNumEdgeWeights() const { return ne_; }
  int GetNumFaceWeights() const { return nf_; }
  void SetNumVertexWeights(int n) { nv_ = n; }
  void SetNumEdgeWeights(int n) { ne_ = n, grow(e_, n); }
  void SetNumFaceWeights(int n) { nf_ = n, grow(f_, n); }
  Weight const& VertexWeight(int i) const { return v_[i]; }
  Weight const& EdgeWeight(int i) const { return e_[i]; }
  Weight const& FaceWeight(int i) const { return f_[i]; }
  Weight& VertexWeight(int i) { return v_[i]; }
  Weight& EdgeWeight(int i) { return e_[i]; }
  Weight& FaceWeight(int i) { return f_[i]; }
  bool AreFaceWeightsForFaceCenters() const { return centres_; }
  void SetFaceWeightsForFaceCenters(bool on) { centres_ = on; }

  // In double: a pole's ring of 360 terms summed in float is off by 1e-6 of the diagonal.
  V3 apply(const VertexDisk& d) const {
    Sum r;
    r.add(v_[0], d.c);
    for (int i = 0; i < ne_; ++i) r.add(e_[i], d.e[i]);
    for (int i = 0; i < nf_; ++i) {
      if (!centres_) {
        r.add(f_[i], d.d[i]);
        continue;
      }
      const V3 corners[4] = {d.c, d.e[i], d.d[i], d.e[(i + 1) % d.edges]};
      for (const V3& p : corners) r.add(0.25 * f_[i], p);
    }
    return r.get();
  }
  V3 apply(const EdgeDisk& d) const {
    Sum r;
    r.add(v_[0], d.v0);
    r.add(v_[1], d.v1);
    for (int i = 0; i < nf_; ++i) {
      if (!centres_) {  // a triangle's opposite corner (Loop)
        r.add(f_[i], d.f[i][0]);
        continue;
      }
      const V3 corners[4] = {d.v0, d.v1, d.f[i][0], d.f[i][1]};
      for (const V3& p : corners) r.add(0.25 * f_[i], p);
    }
    return r.get();
  }

 private:
  static void grow(std::vector<Weight>& w, int n) {
    if (w.size() < size_t(n)) w.resize(n);
  }
  Weight v_[2] = {0, 0};
  std::vector<Weight> e_, f_;
  int nv_ = 0, ne_ = 0, nf_ = 0;
  bool centres_ = false;
};

thread_local Mask t_pos, t_tan1, t_tan2;

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
    const Sdc::Scheme<kType> scheme(options_);
    scheme.ComputeVertexVertexMask(SdcVertex(disk), t_pos);
    return t_pos.apply(disk);
  }

  V3 edge_vertex(const EdgeDisk& disk) const override {
    const Sdc::Scheme<kType> scheme(options_);
    scheme.ComputeEdgeVertexMask(SdcEdge(disk, kType == Sdc::SCHEME_CATMARK ? 4 : 3), t_pos);
    return t_pos.apply(disk);
  }

  void limit(const VertexDisk& disk, V3& position, V3& normal) const override {
    const Sdc::Crease crease(options_);
    const Sdc::Crease::Rule rule = crease.DetermineVertexVertexRule(disk.sharpness, disk.edges, disk.edge_sharpness.data());
    const Sdc::Scheme<kType> scheme(options_);
    scheme.ComputeVertexLimitMask(SdcVertex(disk), t_pos, t_tan1, t_tan2, rule);
    position = t_pos.apply(disk);
    normal = normalized(cross(t_tan1.apply(disk), t_tan2.apply(disk)));
  }

 private:
  Sdc::Options options_;
};

}  // namespace

std::unique_ptr<MeshShader> make_shader(SubdivisionRule rule, const Sdc::Options& options) {
  if (rule == SubdivisionRule::Loop) return std::make_unique<SdcShader<Sdc::SCHEME_LOOP>>(options);
  return std::make_unique<SdcShader<Sdc::SCHEME_CATMARK>>(options);
}

}  // namespace sdb::mipgh
