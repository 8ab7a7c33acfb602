// A mask as OpenSubdiv's Sdc::Scheme fills it (the MASK interface of ComputeEdgeVertexMask,
// ComputeVertexVertexMask and ComputeVertexLimitMask): weights of the vertex or edge ends, of the
// edges' far ends and of the faces (face centres or the faces' opposite corners, as the scheme
// says). Shared by the schemes that take their crease rules from Sdc (fragments, mipgh).
#pragma once

#include <vector>

namespace sdb {

class SdcMask {
 public:
  using Weight = float;
  // `reserve`: weights kept ready per kind (they grow past it as a mask asks for more).
  explicit SdcMask(int reserve = 0) : e_(reserve), f_(reserve) {}
  int GetNumVertexWeights() const { return nv_; }
  int GetNumEdgeWeights() const { return ne_; }
  int GetNumFaceWeights() const { return nf_; }
  void SetNumVertexWeights(int n) { nv_ = n; }  // an edge's mask has two, a vertex's one
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

 private:
  static void grow(std::vector<Weight>& w, int n) {
    if (w.size() < size_t(n)) w.resize(n);
  }
  Weight v_[2] = {0, 0};
  std::vector<Weight> e_, f_;
  int nv_ = 0, ne_ = 0, nf_ = 0;
  bool centres_ = false;
};

}  // namespace sdb
