#include "harness/mesh/placement.h"

#include <algorithm>
#include <cmath>

#include "harness/core/errors.h"

namespace sdb {
namespace {

// Below these, in placed coordinates (diagonal about 1), a length or an area is float's rounding
// of zero: float resolves about 6e-8 at 1.
constexpr double kZeroLength = 1e-7;
constexpr double kZeroArea = 1e-14;

using Vec = std::array<double, 3>;

Vec placed(const Placement& p, const Point3& x) {
  return {(x[0] - p.centre[0]) * p.scale, (x[1] - p.centre[1]) * p.scale, (x[2] - p.centre[2]) * p.scale};
}
Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Vec& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

std::vector<char> used_vertices(const ControlMesh& m) {
  std::vector<char> used(m.positions.size(), 0);
  for (int v : m.face_vertices)
    if (v >= 0 && v < num_vertices(m)) used[v] = 1;
  return used;
}

// Twice the area of face f, in placed coordinates (Newell's vector sum: any polygon, planar or not).
double twice_area(const ControlMesh& m, const std::vector<int>& off, int f, const Placement& p) {
  Vec sum{0, 0, 0};
  const Vec first = placed(p, m.positions[m.face_vertices[off[f]]]);
  for (int k = off[f] + 1; k + 1 < off[f + 1]; ++k) {
    const Vec c = cross(sub(placed(p, m.positions[m.face_vertices[k]]), first),
                        sub(placed(p, m.positions[m.face_vertices[k + 1]]), first));
    for (int i = 0; i < 3; ++i) sum[i] += c[i];
  }
  return norm(sum);
}

// Whether every used vertex lies within kZeroLength of the line through two of them far apart.
bool collinear(const ControlMesh& m, const std::vector<char>& used, const Placement& p) {
  const int first = static_cast<int>(std::find(used.begin(), used.end(), 1) - used.begin());
  const Vec a = placed(p, m.positions[first]);
  Vec far = a;
  for (int v = 0; v < num_vertices(m); ++v)
    if (used[v] && norm(sub(placed(p, m.positions[v]), a)) > norm(sub(far, a))) far = placed(p, m.positions[v]);
  const Vec axis = sub(far, a);
  const double length = norm(axis);
  for (int v = 0; v < num_vertices(m); ++v)
    if (used[v] && norm(cross(sub(placed(p, m.positions[v]), a), axis)) > kZeroLength * length) return false;
  return true;
}

// The first face whose vertices, two or more distinct ones, all lie at one point; -1 if none.
int first_coincident_face(const ControlMesh& m, const std::vector<int>& off) {
  for (int f = 0; f < num_faces(m); ++f) {
    const int a = m.face_vertices[off[f]];
    bool distinct = false, same_place = true;
    for (int k = off[f] + 1; k < off[f + 1] && same_place; ++k) {
      const int b = m.face_vertices[k];
      distinct |= b != a;
      same_place = m.positions[b] == m.positions[a];
    }
    if (distinct && same_place) return f;
  }
  return -1;
}

}  // namespace

Bounds used_bounds(const ControlMesh& m) {
  const std::vector<char> used = used_vertices(m);
  std::vector<Point3> points;
  for (size_t v = 0; v < used.size(); ++v)
    if (used[v]) points.push_back(m.positions[v]);
  return bounds_of(points);
}

Point3 Placement::original(const Point3& p) const {
  return {static_cast<float>(p[0] / scale + centre[0]), static_cast<float>(p[1] / scale + centre[1]),
          static_cast<float>(p[2] / scale + centre[2])};
}

Placement placement_of(const ControlMesh& m) {
  const Bounds b = used_bounds(m);
  Placement p;
  for (int k = 0; k < 3; ++k) p.centre[k] = b.centre(k);
  const double diagonal = b.diagonal();
  if (diagonal > 0 && std::isfinite(diagonal)) p.scale = std::ldexp(1.0, -static_cast<int>(std::lround(std::log2(diagonal))));
  return p;
}

std::optional<std::string> degenerate_geometry(const ControlMesh& m) {
  const std::vector<char> used = used_vertices(m);
  const long n_used = std::count(used.begin(), used.end(), 1);
  const std::string judged = ": no scheme's output can be judged against it";
  if (used_bounds(m).diagonal() == 0)
    return m.source + ": degenerate geometry: the " + std::to_string(n_used) + " vertices the faces use all lie at one point" + judged;
  const Placement p = placement_of(m);
  if (collinear(m, used, p))
    return m.source + ": degenerate geometry: the mesh is collapsed to a line (its " + std::to_string(n_used) +
           " vertices lie on one)" + judged;
  const auto off = face_offsets(m);
  bool any_area = false;
  for (int f = 0; f < num_faces(m) && !any_area; ++f) any_area = twice_area(m, off, f, p) > 2 * kZeroArea;
  if (!any_area) return m.source + ": degenerate geometry: every face has zero area" + judged;
  if (const int f = first_coincident_face(m, off); f >= 0)
    return face_location(m, f) + ": degenerate geometry: the face's " + std::to_string(m.face_sizes[f]) +
           " vertices lie at one point (coincident vertices), so it has no size to state a deviation against";
  return std::nullopt;
}

ControlMesh placed_mesh(const ControlMesh& mesh) {
  if (auto why = degenerate_geometry(mesh)) throw InputError("", *why);
  const Placement p = placement_of(mesh);
  ControlMesh out = mesh;
  for (auto& x : out.positions) {
    const Vec v = placed(p, x);
    x = {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
  }
  return out;
}

}  // namespace sdb
