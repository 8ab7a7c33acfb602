#include "schemes/geometry-image/creation/fit.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sdb::gim {

namespace {

// Uniform cubic B-spline weights of the four control points i-1 .. i+2 at s = i + u.
void bspline_weights(double u, double w[4]) {
  const double u2 = u * u, u3 = u2 * u, v = 1.0 - u;
  w[0] = v * v * v / 6.0;
  w[1] = (3 * u3 - 6 * u2 + 4) / 6.0;
  w[2] = (-3 * u3 + 3 * u2 + 3 * u + 1) / 6.0;
  w[3] = u3 / 6.0;
}

// Cell and local coordinate of image coordinate s in [0, n-1].
void locate(double s, int n, int& cell, double& u) {
  cell = std::clamp(static_cast<int>(std::floor(s)), 0, n - 2);
  u = s - cell;
}

using Term = std::pair<int, double>;  // (free variable, weight)

// Each closed-mesh vertex as a combination of free variables: itself, or for a cut vertex the
// quarter-weighted free variables of equation (2).
struct Unknowns {
  std::vector<std::vector<Term>> of_vertex;
  std::vector<int> vertex_of_variable;
  int count = 0;
};

Unknowns eliminate_cut_vertices(const CutSymmetry& sym) {
  Unknowns u;
  std::vector<char> is_cut(sym.num_vertices(), 0);
  for (const ImagePos& c : sym.cut_vertices()) is_cut[sym.vertex(c.x, c.y)] = 1;
  std::vector<int> variable(sym.num_vertices(), -1);
  for (int v = 0; v < sym.num_vertices(); ++v)
    if (!is_cut[v]) {
      variable[v] = u.count++;
      u.vertex_of_variable.push_back(v);
    }
  u.of_vertex.resize(sym.num_vertices());
  for (int v = 0; v < sym.num_vertices(); ++v)
    if (!is_cut[v]) u.of_vertex[v] = {{variable[v], 1.0}};
  for (int i = 0; i < 4; ++i) {
    const ImagePos c = sym.cut_vertices()[i];
    auto& terms = u.of_vertex[sym.vertex(c.x, c.y)];
    for (const ImagePos& q : sym.cut_vertex_neighbours(i)) {
      const int nv = variable[sym.vertex(q.x, q.y)];
      if (nv < 0) throw std::invalid_argument("image too small: a cut vertex neighbours another");
      terms.push_back({nv, 0.25});
    }
  }
  return u;
}

// One canonical image position per closed-mesh vertex.
std::vector<ImagePos> canonical_positions(const CutSymmetry& sym) {
  std::vector<ImagePos> pos(sym.num_vertices());
  for (int y = 0; y < sym.size(); ++y)
    for (int x = 0; x < sym.size(); ++x)
      if (sym.is_canonical(x, y)) pos[sym.vertex(x, y)] = {x, y};
  return pos;
}

using Triplets = std::vector<Eigen::Triplet<double>>;

// Data term rows: one per dense sample, the 16 B-spline weights spread onto free variables.
void data_rows(const CutSymmetry& sym, const Unknowns& unknowns, const DenseSamples& samples, Triplets& out) {
  const int n = sym.size(), side = samples.side;
  const double to_image = static_cast<double>(n - 1) / (side - 1);
  out.reserve(static_cast<size_t>(side) * side * 18);
  for (int j = 0; j < side; ++j) {
    int cy;
    double v;
    locate(j * to_image, n, cy, v);
    double wy[4];
    bspline_weights(v, wy);
    for (int i = 0; i < side; ++i) {
      int cx;
      double u;
      locate(i * to_image, n, cx, u);
      double wx[4];
      bspline_weights(u, wx);
      const int row = j * side + i;
      for (int b = 0; b < 4; ++b)
        for (int a = 0; a < 4; ++a) {
          const double w = wx[a] * wy[b];
          if (w == 0.0) continue;
          for (const Term& t : unknowns.of_vertex[sym.vertex(cx - 1 + a, cy - 1 + b)])
            out.emplace_back(row, t.first, w * t.second);
        }
    }
  }
}

// Fairness rows: g_v minus the centroid of its four edge neighbours, for each free vertex.
void fairness_rows(const CutSymmetry& sym, const Unknowns& unknowns, Triplets& out) {
  const std::vector<ImagePos> where = canonical_positions(sym);
  for (int var = 0; var < unknowns.count; ++var) {
    const ImagePos p = where[unknowns.vertex_of_variable[var]];
    out.emplace_back(var, var, 1.0);
    const ImagePos steps[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (const ImagePos& s : steps)
      for (const Term& t : unknowns.of_vertex[sym.vertex(p.x + s.x, p.y + s.y)])
        out.emplace_back(var, t.first, -0.25 * t.second);
  }
}

GeometryImage image_from_variables(const CutSymmetry& sym, const Unknowns& unknowns, const Eigen::MatrixXd& x) {
  const int n = sym.size();
  std::vector<Point3> vertex(sym.num_vertices());
  for (int v = 0; v < sym.num_vertices(); ++v) {
    double p[3] = {0, 0, 0};
    for (const Term& t : unknowns.of_vertex[v])
      for (int k = 0; k < 3; ++k) p[k] += t.second * x(t.first, k);
    vertex[v] = {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])};
  }
  GeometryImage image(n);
  for (int y = 0; y < n; ++y)
    for (int xx = 0; xx < n; ++xx) image.at(xx, y) = vertex[sym.vertex(xx, y)];
  return image;
}

}  // namespace

int dense_sample_side(int n) {
  const int per_cell = std::max(4, (256 + n - 2) / (n - 1));
  return per_cell * (n - 1) + 1;
}

GeometryImage fit_geometry_image(int n, const DenseSamples& samples, const FitOptions& options, FitReport* report,
                                 const ClosestOnSurface& closest) {
  const CutSymmetry sym(n);
  if (n < 5) throw std::invalid_argument("fitting needs an image of at least 5 x 5");
  if (samples.side < 2 || samples.points.size() != static_cast<size_t>(samples.side) * samples.side)
    throw std::invalid_argument("dense samples: wrong count");
  const Unknowns unknowns = eliminate_cut_vertices(sym);
  const long k = static_cast<long>(samples.points.size());

  Triplets triplets;
  data_rows(sym, unknowns, samples, triplets);
  Eigen::SparseMatrix<double, Eigen::RowMajor> basis(k, unknowns.count);
  basis.setFromTriplets(triplets.begin(), triplets.end());
  triplets.clear();
  fairness_rows(sym, unknowns, triplets);
  Eigen::SparseMatrix<double> fair(unknowns.count, unknowns.count);
  fair.setFromTriplets(triplets.begin(), triplets.end());
  Triplets().swap(triplets);

  Eigen::MatrixXd target(k, 3);
  for (long i = 0; i < k; ++i)
    for (int c = 0; c < 3; ++c) target(i, c) = samples.points[i][c];

  const Eigen::SparseMatrix<double> bt = basis.transpose();
  Eigen::SparseMatrix<double> normal = (bt * basis) * (1.0 / k);
  normal += (fair.transpose() * fair) * (options.fairness / unknowns.count);

  // Initial guess: the surface at the image's grid points (they are among the dense samples).
  const std::vector<ImagePos> where = canonical_positions(sym);
  const int stride = (samples.side - 1) / (n - 1);
  Eigen::MatrixXd x(unknowns.count, 3);
  for (int var = 0; var < unknowns.count; ++var) {
    const ImagePos p = where[unknowns.vertex_of_variable[var]];
    const Vec3d& s = samples.points[static_cast<size_t>(p.y * stride) * samples.side + p.x * stride];
    for (int c = 0; c < 3; ++c) x(var, c) = s[c];
  }

  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
  cg.setTolerance(options.tolerance);
  cg.setMaxIterations(options.max_iterations);
  cg.compute(normal);
  FitReport r;
  const int rounds = closest ? 1 + std::max(0, options.reprojections) : 1;
  for (int round = 0; round < rounds; ++round) {
    if (round > 0) {
      const Eigen::MatrixXd patch = basis * x;
      tbb::parallel_for(tbb::blocked_range<long>(0, k, 1024), [&](const tbb::blocked_range<long>& range) {
        for (long i = range.begin(); i < range.end(); ++i) {
          const Vec3d q = closest({patch(i, 0), patch(i, 1), patch(i, 2)});
          for (int c = 0; c < 3; ++c) target(i, c) = q[c];
        }
      });
    }
    const Eigen::MatrixXd rhs = (bt * target) * (1.0 / k);
    for (int c = 0; c < 3; ++c) {
      x.col(c) = cg.solveWithGuess(rhs.col(c), x.col(c));
      r.iterations = std::max(r.iterations, static_cast<int>(cg.iterations()));
      r.cg_error = std::max(r.cg_error, cg.error());
    }
  }

  const Eigen::MatrixXd residual = basis * x - target;
  r.samples = k;
  r.unknowns = unknowns.count;
  r.rms_residual = std::sqrt(residual.rowwise().squaredNorm().mean());
  r.max_residual = std::sqrt(residual.rowwise().squaredNorm().maxCoeff());
  if (report) *report = r;
  return image_from_variables(sym, unknowns, x);
}

Vec3d evaluate_patch(const GeometryImage& image, double s, double t) {
  const CutSymmetry sym(image.size);
  int cx, cy;
  double u, v;
  locate(s, image.size, cx, u);
  locate(t, image.size, cy, v);
  double wx[4], wy[4];
  bspline_weights(u, wx);
  bspline_weights(v, wy);
  Vec3d p{0, 0, 0};
  for (int b = 0; b < 4; ++b)
    for (int a = 0; a < 4; ++a) {
      const ImagePos q = sym.fold(cx - 1 + a, cy - 1 + b);
      const Point3& g = image.at(q.x, q.y);
      for (int c = 0; c < 3; ++c) p[c] += wx[a] * wy[b] * g[c];
    }
  return p;
}

}  // namespace sdb::gim
