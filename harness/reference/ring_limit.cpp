#include "harness/reference/ring_limit.h"

#include <opensubdiv/sdc/catmarkScheme.h>
#include <opensubdiv/sdc/loopScheme.h>
#include <opensubdiv/sdc/scheme.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>
#include <unordered_map>

#include "harness/reference/sdc_hoods.h"

namespace sdb {
namespace {

// One level of Sdc's rules on v's ring, which they map to the next level's ring: the vertex
// itself, the points of its edges (the next ring's edge ends) and (Catmull-Clark) the points of
// its faces (the next ring's opposite vertices). The rules are the last level's, taken to repeat.
template <Sdc::SchemeType S>
class RingMatrix {
 public:
  RingMatrix(const Far::TopologyLevel& level, const Sdc::Options& options, int v, int start)
      : l_(level), scheme_(options), v_(v), start_(start), ne_(level.GetVertexEdges(v).size()),
        nf_(kCatmark ? level.GetVertexFaces(v).size() : 0), size_(1 + ne_ + nf_),
        m_(static_cast<size_t>(size_) * size_, 0.0) {
    index_ring();
    vertex_row();
    for (int k = 0; k < ne_; ++k) edge_row(k);
    for (int k = 0; k < nf_; ++k) face_centre(l_.GetVertexFaces(v_)[(k + start_) % nf_], 1 + ne_ + k, 1.0);
  }

  int size() const { return size_; }
  double operator()(int r, int c) const { return m_[static_cast<size_t>(r) * size_ + c]; }
  // Ring index of a vertex of the ring.
  int index_of(int vertex) const { return at_.at(vertex); }

  // l^T M = l^T, normalised to sum 1.
  std::vector<double> left_eigenvector() const {
    std::vector<double> w(size_, 1.0 / size_), next(size_);
    for (int iteration = 0; iteration < 2000; ++iteration) {
      std::fill(next.begin(), next.end(), 0.0);
      for (int r = 0; r < size_; ++r)
        for (int c = 0; c < size_; ++c) next[c] += w[r] * (*this)(r, c);
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
    for (int k = 0; k < ne_; ++k) {
      Far::ConstIndexArray ends = l_.GetEdgeVertices(ve[(k + start_) % ne_]);
      at_[ends[0] == v_ ? ends[1] : ends[0]] = 1 + k;
    }
    for (int k = 0; k < nf_; ++k) {
      const int f = (k + start_) % nf_;
      Far::ConstIndexArray fv = l_.GetFaceVertices(vf[f]);
      at_[fv[(in_face[f] + 2) % fv.size()]] = 1 + ne_ + k;
    }
  }

  double& at(int row, int vertex) { return m_[static_cast<size_t>(row) * size_ + at_.at(vertex)]; }

  void face_centre(int face, int row, double w) {
    Far::ConstIndexArray fv = l_.GetFaceVertices(face);
    for (int u : fv) at(row, u) += w / fv.size();
  }

  void vertex_row() {
    Far::ConstIndexArray ve = l_.GetVertexEdges(v_), vf = l_.GetVertexFaces(v_);
    SdcMask mask(std::max(ne_, static_cast<int>(vf.size())) + 1);
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
    const int e = l_.GetVertexEdges(v_)[(k + start_) % ne_];
    Far::ConstIndexArray ev = l_.GetEdgeVertices(e), ef = l_.GetEdgeFaces(e);
    SdcMask mask(std::max(2, ef.size()));
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
  int v_, start_, ne_, nf_, size_;
  std::vector<double> m_;
  std::unordered_map<int, int> at_;
};

using Complex = std::complex<double>;

// One eigenvalue's real directions: for a real eigenvalue its left (l) and right (r) vectors, for
// a complex pair the real and imaginary parts, scaled so that the ring's offset from v expands as
// sum r[i] (l . P) over them.
struct Directions {
  double modulus, value;  // |lambda|, and lambda where it is real
  std::vector<Eigen::VectorXd> left, right;
};

std::vector<Directions> eigen_directions(const Eigen::MatrixXd& m) {
  Eigen::EigenSolver<Eigen::MatrixXd> solver(m);
  const Eigen::VectorXcd lambda = solver.eigenvalues();
  const Eigen::MatrixXcd right = solver.eigenvectors();
  const Eigen::MatrixXcd left = right.inverse();  // rows: left eigenvectors with l . r = 1
  std::vector<Directions> out;
  for (int k = 0; k < lambda.size(); ++k) {
    // A defective real eigenvalue comes out as a pair 1e-9 apart: real, for the Jordan test below.
    const bool real = std::abs(lambda[k].imag()) <= 1e-6;
    if (!real && lambda[k].imag() < 0) continue;  // its conjugate stands for both
    Directions d{std::abs(lambda[k]), lambda[k].real(), {}, {}};
    const Eigen::VectorXcd l = left.row(k).transpose(), r = right.col(k);
    if (real) {
      d.left = {l.real()}, d.right = {r.real()};
    } else {  // r (l . P) + conj: 2 Re(r) (Re(l) . P) - 2 Im(r) (Im(l) . P)
      d.left = {2 * l.real(), -2 * l.imag()}, d.right = {r.real(), r.imag()};
    }
    out.push_back(std::move(d));
  }
  std::stable_sort(out.begin(), out.end(), [](const Directions& a, const Directions& b) { return a.modulus > b.modulus; });
  return out;
}

// Where a real eigenvalue's eigenvectors do not span its space (a Jordan block), the spectral
// projector onto its generalised eigenspace (the null space of (M - lambda)^g, along the range) and
// the nilpotent part (M - lambda) P of M there.
struct JordanParts {
  Eigen::MatrixXd projector, nilpotent;
};
JordanParts jordan_parts(const Eigen::MatrixXd& m, double lambda, int multiplicity) {
  const int n = static_cast<int>(m.rows());
  const Eigen::MatrixXd a = m - lambda * Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd power = Eigen::MatrixXd::Identity(n, n);
  for (int k = 0; k < multiplicity; ++k) power = power * a;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(power, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::MatrixXd basis(n, n);
  basis << svd.matrixV().rightCols(multiplicity), svd.matrixU().leftCols(n - multiplicity);
  Eigen::MatrixXd keep = Eigen::MatrixXd::Zero(n, n);
  keep.topLeftCorner(multiplicity, multiplicity).setIdentity();
  const Eigen::MatrixXd projector = basis * keep * basis.inverse();
  return {projector, a * projector};
}

// The refined ring leaves v as sum over eigenvalues of lambda^K (S + K N / lambda) . P, where
// S = r l^T (the projector onto lambda's eigenvectors) and N is the nilpotent part of a Jordan
// block (none where the eigenvectors span). The face's corner at v, its ring neighbours a (after
// v in the face) and b (before), moves by D_a = (e_a - e_v) M^K P, and the face's normal at v is
// the limit of D_a x D_b. Taking the terms in decreasing order (|lambda|, then K before 1): where
// the leading term moves a and b independently, D_a x D_b tends to X_a x X_b, X_. = (e_. - e_v) X
// for that term; where it moves both along one functional T only (X_a = u_a T, X_b = u_b T), the
// next term Y decides: D_a x D_b ~ T x (u_a Y_b - u_b Y_a).
template <Sdc::SchemeType S>
RingTangents tangents(const Far::TopologyLevel& level, const Sdc::Options& options, int v, int face) {
  const RingMatrix<S> ring(level, options, v, 0);
  const int n = ring.size();
  Eigen::MatrixXd m(n, n);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) m(r, c) = ring(r, c);
  const int f = level.GetVertexFaces(v)[face];
  Far::ConstIndexArray fv = level.GetFaceVertices(f);
  const int i = level.GetVertexFaceLocalIndices(v)[face], size = fv.size();
  const int a = ring.index_of(fv[(i + 1) % size]), b = ring.index_of(fv[(i + size - 1) % size]);
  Eigen::VectorXd lead;  // T, once a term moved the corner along one functional
  double ua = 0, ub = 0;
  // One term of the expansion; the tangents once they are decided.
  auto take = [&](const Eigen::VectorXd& xa, const Eigen::VectorXd& xb) -> std::optional<RingTangents> {
    const double scale = std::max(xa.norm(), xb.norm());
    if (lead.size()) {
      const Eigen::VectorXd second = ua * xb - ub * xa;
      if (second.norm() <= 1e-7 * scale || scale < 1e-12) return std::nullopt;
      return RingTangents{{lead.data(), lead.data() + n}, {second.data(), second.data() + n}};
    }
    if (scale < 1e-9) return std::nullopt;  // does not move this face's corner
    Eigen::MatrixXd pair(2, n);
    pair.row(0) = xa.transpose(), pair.row(1) = xb.transpose();
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(pair, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::VectorXd sigma = svd.singularValues();
    if (sigma[1] > 1e-7 * sigma[0]) return RingTangents{{xa.data(), xa.data() + n}, {xb.data(), xb.data() + n}};
    ua = svd.matrixU()(0, 0), ub = svd.matrixU()(1, 0);
    lead = sigma[0] * svd.matrixV().col(0);
    return std::nullopt;
  };
  const std::vector<Directions> directions = eigen_directions(m);
  for (size_t c = 0; c < directions.size();) {
    // One cluster of equal |lambda|.
    size_t end = c;
    while (end < directions.size() && std::abs(directions[end].modulus - directions[c].modulus) < 1e-6) ++end;
    if (std::abs(directions[c].modulus - 1) < 1e-6) {  // the position (the masks are floats)
      c = end;
      continue;
    }
    Eigen::VectorXd sa = Eigen::VectorXd::Zero(n), sb = Eigen::VectorXd::Zero(n);
    Eigen::MatrixXd span(n, 0);
    bool real = true;
    double lambda = 0;
    int count = 0;
    for (size_t k0 = c; k0 < end; ++k0) {
      const Directions& d = directions[k0];
      real &= d.left.size() == 1;
      lambda += d.value, ++count;
      for (size_t k = 0; k < d.left.size(); ++k) {
        const Eigen::VectorXd &l = d.left[k], &r = d.right[k];
        sa += (r[a] - r[0]) * l, sb += (r[b] - r[0]) * l;
        span.conservativeResize(n, span.cols() + 1);
        span.col(span.cols() - 1) = r;
      }
    }
    c = end;
    const Eigen::VectorXd spread = Eigen::JacobiSVD<Eigen::MatrixXd>(span).singularValues();
    if (spread[spread.size() - 1] < 1e-6 * spread[0]) {  // a Jordan block
      if (!real) return {};
      const JordanParts j = jordan_parts(m, lambda / count, count);
      const Eigen::VectorXd na = (j.nilpotent.row(a) - j.nilpotent.row(0)).transpose() / (lambda / count);
      const Eigen::VectorXd nb = (j.nilpotent.row(b) - j.nilpotent.row(0)).transpose() / (lambda / count);
      if (auto t = take(na, nb)) return *t;
      sa = (j.projector.row(a) - j.projector.row(0)).transpose();
      sb = (j.projector.row(b) - j.projector.row(0)).transpose();
    }
    if (auto t = take(sa, sb)) return *t;
  }
  return {};
}

}  // namespace

std::vector<double> ring_limit_weights(const Far::TopologyLevel& level, const Sdc::Options& options, bool catmark, int v,
                                       int start) {
  if (catmark) return RingMatrix<Sdc::SCHEME_CATMARK>(level, options, v, start).left_eigenvector();
  return RingMatrix<Sdc::SCHEME_LOOP>(level, options, v, start).left_eigenvector();
}

RingTangents ring_limit_tangents(const Far::TopologyLevel& level, const Sdc::Options& options, bool catmark, int v,
                                 int face) {
  if (catmark) return tangents<Sdc::SCHEME_CATMARK>(level, options, v, face);
  return tangents<Sdc::SCHEME_LOOP>(level, options, v, face);
}

std::vector<int> ring_limit_vertices(const Far::TopologyLevel& l, int v, bool catmark, int start) {
  std::vector<int> out = {v};
  Far::ConstIndexArray ve = l.GetVertexEdges(v), vf = l.GetVertexFaces(v);
  for (int k = 0; k < ve.size(); ++k) {
    Far::ConstIndexArray ends = l.GetEdgeVertices(ve[(k + start) % ve.size()]);
    out.push_back(ends[0] == v ? ends[1] : ends[0]);
  }
  if (!catmark) return out;
  Far::ConstLocalIndexArray in = l.GetVertexFaceLocalIndices(v);
  for (int k = 0; k < vf.size(); ++k) {
    const int f = (k + start) % vf.size();
    Far::ConstIndexArray fv = l.GetFaceVertices(vf[f]);
    out.push_back(fv[(in[f] + 2) % fv.size()]);
  }
  return out;
}

template <Sdc::SchemeType S>
std::vector<double> matrix_of(const Far::TopologyLevel& level, const Sdc::Options& options, int v) {
  const RingMatrix<S> ring(level, options, v, 0);
  std::vector<double> m;
  for (int r = 0; r < ring.size(); ++r)
    for (int c = 0; c < ring.size(); ++c) m.push_back(ring(r, c));
  return m;
}

std::vector<double> ring_subdivision_matrix(const Far::TopologyLevel& level, const Sdc::Options& options, bool catmark,
                                            int v) {
  return catmark ? matrix_of<Sdc::SCHEME_CATMARK>(level, options, v) : matrix_of<Sdc::SCHEME_LOOP>(level, options, v);
}

}  // namespace sdb
