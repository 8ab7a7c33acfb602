#include "schemes/fragments/ring_limit.h"

#include <opensubdiv/sdc/catmarkScheme.h>
#include <opensubdiv/sdc/loopScheme.h>
#include <opensubdiv/sdc/scheme.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "schemes/fragments/sdc_masks.h"

namespace sdb::fragments {
namespace {

template <Sdc::SchemeType S>
class RingMatrix {
 public:
  RingMatrix(const Far::TopologyLevel& level, const Sdc::Options& options, int v, int start)
      : l_(level), scheme_(options), v_(v), start_(start), n_(level.GetVertexEdges(v).size()),
        size_(1 + n_ + (kCatmark ? n_ : 0)), m_(static_cast<size_t>(size_) * size_, 0.0) {
    index_ring();
    vertex_row();
    for (int k = 0; k < n_; ++k) edge_row(k);
    if (kCatmark)
      for (int k = 0; k < n_; ++k) face_centre(l_.GetVertexFaces(v_)[(k + start_) % n_], 1 + n_ + k, 1.0);
  }

  // l^T M = l^T, normalised to sum 1.
  std::vector<double> left_eigenvector() const {
    std::vector<double> w(size_, 1.0 / size_), next(size_);
    for (int iteration = 0; iteration < 2000; ++iteration) {
      std::fill(next.begin(), next.end(), 0.0);
      for (int r = 0; r < size_; ++r)
        for (int c = 0; c < size_; ++c) next[c] += w[r] * m_[static_cast<size_t>(r) * size_ + c];
      double sum = 0, change = 0;
      for (double x : next) sum += x;
      for (int c = 0; c < size_; ++c) next[c] /= sum, change = std::max(change, std::abs(next[c] - w[c]));
      w.swap(next);
      if (change < 1e-16) break;
    }
    return w;
  }

 private:
  static constexpr bool kCatmark = S == Sdc::SCHEME_CATMARK;

  void index_ring() {
    Far::ConstIndexArray ve = l_.GetVertexEdges(v_), vf = l_.GetVertexFaces(v_);
    Far::ConstLocalIndexArray in_face = l_.GetVertexFaceLocalIndices(v_);
    at_[v_] = 0;
    for (int k = 0; k < n_; ++k) {
      Far::ConstIndexArray ends = l_.GetEdgeVertices(ve[(k + start_) % n_]);
      at_[ends[0] == v_ ? ends[1] : ends[0]] = 1 + k;
    }
    if (kCatmark)
      for (int k = 0; k < n_; ++k) {
        const int f = (k + start_) % n_;
        Far::ConstIndexArray fv = l_.GetFaceVertices(vf[f]);
        at_[fv[(in_face[f] + 2) % fv.size()]] = 1 + n_ + k;
      }
  }

  double& at(int row, int vertex) { return m_[static_cast<size_t>(row) * size_ + at_.at(vertex)]; }

  void face_centre(int face, int row, double w) {
    Far::ConstIndexArray fv = l_.GetFaceVertices(face);
    for (int u : fv) at(row, u) += w / fv.size();
  }

  void vertex_row() {
    Far::ConstIndexArray ve = l_.GetVertexEdges(v_), vf = l_.GetVertexFaces(v_);
    Mask mask(n_ + 1);
    const Sdc::Crease::Rule rule = l_.GetVertexRule(v_);
    scheme_.ComputeVertexVertexMask(VertexHood(l_, l_, v_, v_), mask, rule, rule);
    at(0, v_) += mask.VertexWeight(0);
    for (int i = 0; i < mask.GetNumEdgeWeights(); ++i) {
      Far::ConstIndexArray ends = l_.GetEdgeVertices(ve[i]);
      at(0, ends[0] == v_ ? ends[1] : ends[0]) += mask.EdgeWeight(i);
    }
    for (int i = 0; i < mask.GetNumFaceWeights(); ++i) face_centre(vf[i], 0, mask.FaceWeight(i));
  }

  void edge_row(int k) {
    const int e = l_.GetVertexEdges(v_)[(k + start_) % n_];
    Far::ConstIndexArray ev = l_.GetEdgeVertices(e), ef = l_.GetEdgeFaces(e);
    Mask mask(2);
    const Sdc::Crease::Rule rule = l_.GetEdgeSharpness(e) > 0 ? Sdc::Crease::RULE_CREASE : Sdc::Crease::RULE_SMOOTH;
    scheme_.ComputeEdgeVertexMask(EdgeHood(l_, e), mask, rule, rule);
    at(1 + k, ev[0]) += mask.VertexWeight(0);
    at(1 + k, ev[1]) += mask.VertexWeight(1);
    for (int i = 0; i < mask.GetNumFaceWeights(); ++i) {
      if (mask.AreFaceWeightsForFaceCenters()) {
        face_centre(ef[i], 1 + k, mask.FaceWeight(i));
        continue;
      }
      Far::ConstIndexArray fe = l_.GetFaceEdges(ef[i]), fv = l_.GetFaceVertices(ef[i]);
      int j = 0;
      while (fe[j] != e) ++j;
      at(1 + k, fv[(j + 2) % fv.size()]) += mask.FaceWeight(i);
    }
  }

  const Far::TopologyLevel& l_;
  Sdc::Scheme<S> scheme_;
  int v_, start_, n_, size_;
  std::vector<double> m_;
  std::unordered_map<int, int> at_;
};

}  // namespace

std::vector<double> ring_limit_weights(const Far::TopologyLevel& level, const Sdc::Options& options, bool catmark, int v,
                                       int start) {
  if (catmark) return RingMatrix<Sdc::SCHEME_CATMARK>(level, options, v, start).left_eigenvector();
  return RingMatrix<Sdc::SCHEME_LOOP>(level, options, v, start).left_eigenvector();
}

}  // namespace sdb::fragments
