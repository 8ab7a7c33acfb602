#include "schemes/geometry-image/creation/parametrize.h"

#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace sdb::gim {

namespace {

using Vec = Vec3d;

Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec add(const Vec& a, const Vec& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec scale(const Vec& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Vec& a) { return std::sqrt(dot(a, a)); }
Vec normalized(const Vec& a) { return scale(a, 1.0 / norm(a)); }
double det3(const Vec& a, const Vec& b, const Vec& c) { return dot(a, cross(b, c)); }

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Per-triangle constants of the stretch energy: surface area and squared surface edge lengths
// (edge k is opposite corner k).
struct TriangleMetric {
  double area = 0;
  double edge2[3] = {0, 0, 0};
  double inverse = 0;  // weight of the inverse-stretch term (see stretch_energy)
};

std::vector<TriangleMetric> triangle_metrics(const TriangleMesh& mesh, double inverse_weight = 0) {
  std::vector<TriangleMetric> out(mesh.triangles.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const Vec& a = mesh.positions[tri[0]];
    const Vec& b = mesh.positions[tri[1]];
    const Vec& c = mesh.positions[tri[2]];
    out[t].area = triangle_area(a, b, c);
    out[t].edge2[0] = dot(sub(c, b), sub(c, b));
    out[t].edge2[1] = dot(sub(a, c), sub(a, c));
    out[t].edge2[2] = dot(sub(b, a), sub(b, a));
  }
  if (inverse_weight > 0) {
    double total = 0;
    for (const TriangleMetric& m : out) total += m.area;
    const double scale = total * total / (64 * std::numbers::pi * std::numbers::pi);
    for (TriangleMetric& m : out)
      if (m.area > 0) m.inverse = inverse_weight * scale / (m.area * m.area);
  }
  return out;
}

// A (|J|^2 + w |J^-1|^2) / 2 for the affine map J from the chord triangle (q0, q1, q2) to the
// surface triangle, with the sphere scaled to the surface's area; infinite when the chord
// triangle faces inwards. |J|^2 = sum_k cot(alpha_k) |e_k|^2 / (2 A_param), cot(alpha_k) =
// (d.d') / (2 A_param) at param corner k, so |J|^2 = s / N with N = (2 A_param)^2. The first term
// is Sander et al.'s L2 stretch (undersampling); the second, |J^-1|^2 = |J|^2 / det(J)^2 for a
// 2 x 2 map, penalises the opposite (a spherical triangle much larger or more elongated than its
// surface triangle) and keeps relaxation out of local minima with slivers. Up to a constant
// factor, A |J^-1|^2 / 2 = A s / 2 * S^2 / (64 pi^2 A^2): linear in s (m.inverse holds the factor).
double stretch_energy(const Vec& q0, const Vec& q1, const Vec& q2, const TriangleMetric& m) {
  if (det3(q0, q1, q2) <= 0.0) return kInfinity;
  const Vec d01 = sub(q1, q0), d02 = sub(q2, q0), d12 = sub(q2, q1);
  const Vec n = cross(d01, d02);
  const double area2x4 = dot(n, n);  // (2 A_param)^2
  if (area2x4 <= 0.0) return kInfinity;
  const double s = dot(d01, d02) * m.edge2[0] - dot(d01, d12) * m.edge2[1] + dot(d02, d12) * m.edge2[2];
  return m.area * 0.5 * s * (1.0 / area2x4 + m.inverse);
}

double chord_area(const Vec& a, const Vec& b, const Vec& c) { return 0.5 * norm(cross(sub(b, a), sub(c, a))); }

// The link of vertex v in rotation order: triangle (v, a, b) counter-clockwise gives a -> b.
std::vector<int> ordered_link(const TriangleMesh& mesh, const std::vector<int>& star, int v) {
  std::vector<std::pair<int, int>> next;
  for (int t : star) {
    const auto& tri = mesh.triangles[t];
    const int k = tri[0] == v ? 0 : tri[1] == v ? 1 : 2;
    next.push_back({tri[(k + 1) % 3], tri[(k + 2) % 3]});
  }
  std::vector<int> link = {next.front().first};
  while (link.size() < next.size()) {
    auto it = std::find_if(next.begin(), next.end(), [&](const auto& e) { return e.first == link.back(); });
    if (it == next.end()) throw std::runtime_error("vertex link is not a single cycle");
    link.push_back(it->second);
  }
  return link;
}

// Steps 1 and 2: Tutte embedding of the mesh minus the star of `pole`, mapped to the sphere
// with `pole` at +z.
std::vector<Vec> tutte_on_sphere(const TriangleMesh& mesh, const std::vector<std::vector<int>>& vt, int pole,
                                 const std::vector<double>& scale) {
  // The link on a circle of radius 1/4: the disk then maps to a small, nearly flat cap, whose
  // chord triangles keep the planar triangles' orientation even on a coarse mesh (a scale of the
  // plane is a Moebius map of the sphere, which the centring undoes anyway).
  constexpr double kRing = 0.25;
  const int nv = static_cast<int>(mesh.positions.size());
  const std::vector<int> link = ordered_link(mesh, vt[pole], pole);
  std::vector<double> px(nv, 0.0), py(nv, 0.0);
  std::vector<int> unknown(nv, -1);
  std::vector<char> fixed(nv, 0);
  fixed[pole] = 1;
  // The disk's boundary runs against the link's rotation, so the link goes clockwise.
  for (size_t i = 0; i < link.size(); ++i) {
    const double angle = -2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(link.size());
    px[link[i]] = kRing * std::cos(angle), py[link[i]] = kRing * std::sin(angle), fixed[link[i]] = 1;
  }
  int count = 0;
  for (int v = 0; v < nv; ++v)
    if (!fixed[v]) unknown[v] = count++;

  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(count, 2);
  // Mean-value weight of corner a towards b: tan(theta_a / 2) / |b - a|.
  auto add_weight = [&](int a, int b, double w) {
    if (unknown[a] < 0) return;
    triplets.emplace_back(unknown[a], unknown[a], w);
    if (unknown[b] >= 0) {
      triplets.emplace_back(unknown[a], unknown[b], -w);
    } else {
      rhs(unknown[a], 0) += w * px[b];
      rhs(unknown[a], 1) += w * py[b];
    }
  };
  for (const auto& tri : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = tri[k], b = tri[(k + 1) % 3], c = tri[(k + 2) % 3];
      const Vec e1 = sub(mesh.positions[b], mesh.positions[a]), e2 = sub(mesh.positions[c], mesh.positions[a]);
      const double l1 = std::max(norm(e1), 1e-300), l2 = std::max(norm(e2), 1e-300);
      const double tan_half = norm(cross(e1, e2)) / std::max(l1 * l2 + dot(e1, e2), 1e-300 * l1 * l2);
      const double t = std::clamp(tan_half, 1e-8, 1e8);
      add_weight(a, b, scale[b] * t / l1);
      add_weight(a, c, scale[c] * t / l2);
    }
  Eigen::SparseMatrix<double> system(count, count);
  system.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(system);
  if (lu.info() != Eigen::Success) throw std::runtime_error("Tutte embedding: factorisation failed");
  const Eigen::MatrixXd xy = lu.solve(rhs);
  for (int v = 0; v < nv; ++v)
    if (unknown[v] >= 0) px[v] = xy(unknown[v], 0), py[v] = xy(unknown[v], 1);

  std::vector<Vec> sphere(nv);
  for (int v = 0; v < nv; ++v) {
    const double r2 = px[v] * px[v] + py[v] * py[v];
    sphere[v] = {2 * px[v] / (r2 + 1), 2 * py[v] / (r2 + 1), (r2 - 1) / (r2 + 1)};
  }
  sphere[pole] = {0, 0, 1};
  // Inverse stereographic projection turns orientation over; mirror to restore it.
  double volume = 0;
  for (const auto& tri : mesh.triangles) volume += det3(sphere[tri[0]], sphere[tri[1]], sphere[tri[2]]);
  if (volume < 0)
    for (Vec& q : sphere) q[0] = -q[0];
  return sphere;
}

int count_folded(const TriangleMesh& mesh, const std::vector<Vec>& sphere) {
  int folded = 0;
  for (const auto& tri : mesh.triangles)
    if (det3(sphere[tri[0]], sphere[tri[1]], sphere[tri[2]]) <= 0.0) ++folded;
  return folded;
}

// Step 3: Moebius centring. phi_c(x) = (1 - |c|^2)(x - c) / |x - c|^2 - c maps the sphere onto
// itself, c to the origin of the ball, and spreads points near c / |c| apart. It maps circles to
// circles, not chords to chords, so on a coarse mesh a chord triangle can turn over: the
// centring stops before a step that would fold one and leaves the rest to the relaxation.
void moebius_centre(const TriangleMesh& mesh, std::vector<Vec>& sphere, const std::vector<double>& weight) {
  double total = 0;
  for (double w : weight) total += w;
  std::vector<Vec> previous;
  const int folded_before = count_folded(mesh, sphere);
  for (int iteration = 0; iteration < 500; ++iteration) {
    previous = sphere;
    Vec mu{0, 0, 0};
    for (size_t v = 0; v < sphere.size(); ++v) mu = add(mu, scale(sphere[v], weight[v] / total));
    if (norm(mu) < 1e-10) break;
    // A half step: the linearised update at a uniform distribution overshoots with a full one.
    const Vec c = scale(mu, 0.5);
    const double c2 = dot(c, c);
    for (Vec& x : sphere) {
      const Vec d = sub(x, c);
      x = normalized(sub(scale(d, (1 - c2) / dot(d, d)), c));
    }
    if (count_folded(mesh, sphere) > folded_before) {
      sphere = previous;
      return;
    }
  }
}

std::vector<double> vertex_areas(const TriangleMesh& mesh, const std::vector<TriangleMetric>& metric) {
  std::vector<double> area(mesh.positions.size(), 0.0);
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int v : mesh.triangles[t]) area[v] += metric[t].area / 3;
  return area;
}

// Step 4, one vertex: the energy of its star as a function of its position.
class StarEnergy {
 public:
  StarEnergy(const TriangleMesh& mesh, const std::vector<TriangleMetric>& metric, std::vector<Vec>& sphere)
      : mesh_(mesh), metric_(metric), sphere_(sphere) {}
  double operator()(const std::vector<int>& star, int v, const Vec& at) const {
    double e = 0;
    for (int t : star) {
      const auto& tri = mesh_.triangles[t];
      const Vec& q0 = tri[0] == v ? at : sphere_[tri[0]];
      const Vec& q1 = tri[1] == v ? at : sphere_[tri[1]];
      const Vec& q2 = tri[2] == v ? at : sphere_[tri[2]];
      e += stretch_energy(q0, q1, q2, metric_[t]);
      if (e == kInfinity) return e;
    }
    return e;
  }
  // Gradient of the star's energy in v's position (not yet projected to the sphere's tangent
  // plane). With v as corner 0 of (q0, q1, q2), E = c s / N, c = A / 2, N = |n|^2,
  // n = (q1 - q0) x (q2 - q0): grad s = e0 (2 q0 - q1 - q2) + (e1 - e2)(q2 - q1) and
  // grad N = 2 (q1 - q2) x n.
  Vec gradient(const std::vector<int>& star, int v) const {
    Vec g{0, 0, 0};
    for (int t : star) {
      const auto& tri = mesh_.triangles[t];
      const int k = tri[0] == v ? 0 : tri[1] == v ? 1 : 2;
      const Vec& q0 = sphere_[tri[k]];
      const Vec& q1 = sphere_[tri[(k + 1) % 3]];
      const Vec& q2 = sphere_[tri[(k + 2) % 3]];
      const double e0 = metric_[t].edge2[k], e1 = metric_[t].edge2[(k + 1) % 3], e2 = metric_[t].edge2[(k + 2) % 3];
      const Vec d01 = sub(q1, q0), d02 = sub(q2, q0), d12 = sub(q2, q1);
      const Vec n = cross(d01, d02);
      const double big_n = dot(n, n);
      const double s = dot(d01, d02) * e0 - dot(d01, d12) * e1 + dot(d02, d12) * e2;
      const Vec grad_s = add(scale(sub(scale(q0, 2.0), add(q1, q2)), e0), scale(d12, e1 - e2));
      const Vec grad_n = scale(cross(sub(q1, q2), n), 2.0);
      const double c = 0.5 * metric_[t].area;
      const Vec term = sub(scale(grad_s, 1.0 / big_n + metric_[t].inverse), scale(grad_n, s / (big_n * big_n)));
      g = add(g, scale(term, c));
    }
    return g;
  }

 private:
  const TriangleMesh& mesh_;
  const std::vector<TriangleMetric>& metric_;
  std::vector<Vec>& sphere_;
};

// Moves vertex v down the gradient of its star's energy (a backtracking line search in the
// tangent plane, from a quarter of its shortest edge); returns the energy decrease.
double relax_vertex(int v, const std::vector<int>& star, const std::vector<int>& neighbours, const StarEnergy& energy,
                    std::vector<Vec>& sphere) {
  const Vec q = sphere[v];
  const double e0 = energy(star, v, q);
  if (!(e0 < kInfinity)) return 0;
  double shortest = kInfinity;
  for (int u : neighbours) shortest = std::min(shortest, norm(sub(sphere[u], q)));
  Vec g = energy.gradient(star, v);
  g = sub(g, scale(q, dot(g, q)));  // tangential part
  const double glen = norm(g);
  if (!(glen > 0) || !std::isfinite(glen)) return 0;
  const Vec direction = scale(g, -1.0 / glen);
  double step = 0.25 * shortest;
  for (int tries = 0; tries < 12; ++tries, step *= 0.5) {
    const Vec candidate = normalized(add(q, scale(direction, step)));
    const double e = energy(star, v, candidate);
    if (e < e0) {
      sphere[v] = candidate;
      return e0 - e;
    }
  }
  return 0;
}

double total_energy(const TriangleMesh& mesh, const std::vector<TriangleMetric>& metric, const std::vector<Vec>& sphere) {
  double e = 0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    e += stretch_energy(sphere[tri[0]], sphere[tri[1]], sphere[tri[2]], metric[t]);
  }
  return e;
}

// Per-vertex L2 stretch: sqrt of the surface-area-weighted mean of |J|^2 / 2 over its triangles.
std::vector<double> vertex_stretch(const TriangleMesh& mesh, const std::vector<TriangleMetric>& metric,
                                   const std::vector<Vec>& sphere) {
  std::vector<double> energy(sphere.size(), 0.0), area(sphere.size(), 0.0);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const double e = stretch_energy(sphere[tri[0]], sphere[tri[1]], sphere[tri[2]], metric[t]);
    for (int v : tri) energy[v] += e, area[v] += metric[t].area;
  }
  std::vector<double> sigma(sphere.size(), 1.0);
  for (size_t v = 0; v < sphere.size(); ++v)
    if (area[v] > 0 && std::isfinite(energy[v])) sigma[v] = std::sqrt(energy[v] / area[v]);
  return sigma;
}

}  // namespace

double l2_stretch(const TriangleMesh& mesh, const std::vector<Vec3d>& sphere) {
  const std::vector<TriangleMetric> metric = triangle_metrics(mesh);
  double surface = 0, param = 0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    surface += metric[t].area;
    param += chord_area(sphere[tri[0]], sphere[tri[1]], sphere[tri[2]]);
  }
  const double e = total_energy(mesh, metric, sphere);
  return std::sqrt(e / surface * param / surface);
}

namespace {

// Step 4 on one level; returns the sweeps made.
int relax(const TriangleMesh& mesh, std::vector<Vec>& sphere, const SphericalParametrizationOptions& options) {
  const std::vector<TriangleMetric> metric = triangle_metrics(mesh, options.inverse_weight);
  const std::vector<std::vector<int>> vt = vertex_triangles(mesh);
  const std::vector<std::vector<int>> nb = vertex_neighbours(mesh);
  StarEnergy energy(mesh, metric, sphere);
  double e = total_energy(mesh, metric, sphere);
  int sweeps = 0;
  while (sweeps < options.max_sweeps && e < kInfinity) {
    ++sweeps;
    double decrease = 0;
    for (int v = 0; v < static_cast<int>(sphere.size()); ++v) decrease += relax_vertex(v, vt[v], nb[v], energy, sphere);
    e = total_energy(mesh, metric, sphere);
    if (decrease < options.tolerance * e) break;
  }
  return sweeps;
}

}  // namespace

SphericalParametrization SphericalParametrization::compute(const TriangleMesh& input,
                                                           const SphericalParametrizationOptions& options) {
  SphericalParametrization out;
  out.surface = input;
  while (out.surface.triangles.size() < options.min_triangles) out.surface = refine_midpoints(out.surface);
  const TriangleMesh mesh = out.surface;
  const std::vector<TriangleMetric> metric = triangle_metrics(mesh);
  const std::vector<std::vector<int>> vt = vertex_triangles(mesh);
  const std::vector<std::vector<int>> nb = vertex_neighbours(mesh);
  const std::vector<double> area = vertex_areas(mesh, metric);
  // The pole: the vertex of highest valence, so that its removed star spans many triangles.
  int pole = 0;
  for (int v = 0; v < static_cast<int>(nb.size()); ++v)
    if (nb[v].size() > nb[pole].size()) pole = v;

  // Stretch-driven reweighting (after Yoshizawa, Belyaev and Seidel 2004): dividing the weights
  // towards a vertex by a power of its stretch lets its neighbours drift away from it, so its
  // triangles grow. Each round is a global solve, so area moves across the whole mesh at once;
  // a round that does not lower the stretch is retried with half the exponent.
  std::vector<double> scale(mesh.positions.size(), 1.0), sigma;
  double best = kInfinity, exponent = 1.0;
  for (int round = 0; round <= options.reweighting_rounds && exponent > 0.05; ++round) {
    std::vector<double> trial = scale;
    for (size_t v = 0; v < sigma.size(); ++v) trial[v] *= std::pow(sigma[v], -exponent);
    std::vector<Vec> sphere = tutte_on_sphere(mesh, vt, pole, trial);
    moebius_centre(mesh, sphere, area);
    const double stretch = l2_stretch(mesh, sphere);
    if (round == 0) {
      out.centred_stretch = stretch;
      // A very elongated shape compresses part of the Tutte embedding beyond double precision
      // (its triangles collapse); nothing below can undo that.
      if (!(stretch < kInfinity)) {
        out.folded_triangles = count_folded(mesh, sphere);
        out.sphere = std::move(sphere);
        out.stretch = kInfinity;
        return out;
      }
    }
    if (!(stretch < best)) {
      exponent *= 0.5;
      continue;
    }
    best = stretch;
    scale = std::move(trial);
    out.sphere = std::move(sphere);
    sigma = vertex_stretch(mesh, metric, out.sphere);
  }
  out.sweeps = relax(mesh, out.sphere, options);
  out.stretch = l2_stretch(out.surface, out.sphere);
  out.folded_triangles = count_folded(out.surface, out.sphere);
  return out;
}

}  // namespace sdb::gim
