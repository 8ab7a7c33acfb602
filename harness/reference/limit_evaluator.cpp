#include "harness/reference/limit_evaluator.h"

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/far/ptexIndices.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>

#include "harness/core/errors.h"
#include "harness/reference/bfr_defect.h"
#include "harness/reference/local_mesh.h"
#include "harness/reference/surface_normal.h"
#include "harness/reference/vertex_limit.h"

namespace sdb {

namespace Bfr = OpenSubdiv::Bfr;
namespace Far = OpenSubdiv::Far;

namespace {

using UV = std::array<double, 2>;

// One step of the descent into a face Bfr does not evaluate exactly: the face (the focus) at some
// level with the faces around its corners, cut out and refined on their own (local_mesh.h), and
// where its corners lie in the base ptex face.
struct Node {
  LocalMesh mesh;
  int focus = 0;                // always face 0 of the cut-out
  std::vector<UV> corner_uv;    // per corner of the focus
  int level = 0;
  bool trusted = false;         // Bfr's surface of the focus is the limit
  Bfr::Surface<double> surface;  // where trusted
  std::vector<double> patch_points;
};

}  // namespace

struct LimitEvaluator::Impl {
  ControlMesh mesh;
  SubdivisionRule rule;
  LimitAccuracy accuracy;
  std::unique_ptr<Far::TopologyRefiner> refiner;
  std::vector<int> ptex_base, ptex_sub;  // per ptex face
  std::vector<int> first_ptex;           // per base face
  std::vector<Bfr::Surface<double>> surfaces;
  std::vector<std::vector<double>> patch_points;  // xyz per patch point, per base face
  std::vector<char> has_limit, trusted;           // per base face
  std::vector<double> local_size;                 // per base face
  std::vector<int> offsets;                       // per base face, into mesh.face_vertices
  std::vector<Point3d> points;                    // the base points in double
  // The exact limit at each base vertex, made on first use.
  std::unique_ptr<std::once_flag[]> vertex_once;
  mutable std::vector<VertexLimit> vertex_limits;
  mutable std::mutex nodes_mutex;
  mutable std::map<std::vector<long>, std::shared_ptr<const Node>> nodes;

  const VertexLimit& vertex(int v) const;
  LimitSample descend(int f, int sub, UV uv) const;
  std::shared_ptr<const Node> root(int f, int sub) const;
  std::shared_ptr<const Node> child(const Node& parent, UV uv) const;
  std::shared_ptr<const Node> make_node(const Far::TopologyLevel& l, const std::vector<Point3d>& points,
                                        const std::vector<char>& marks, int face, std::vector<UV> corner_uv,
                                        int level) const;
  bool face_trusted(const Far::TopologyLevel& l, int f, const std::vector<char>& marks) const;
  std::vector<char> marks;  // per base vertex: non-manifold, at a non-manifold edge, or of valence 2
};

namespace {

double mean_edge_length(const ControlMesh& m, const std::vector<int>& off, int f) {
  const int n = m.face_sizes[f];
  double sum = 0;
  for (int k = 0; k < n; ++k) {
    const auto& a = m.positions[m.face_vertices[off[f] + k]];
    const auto& b = m.positions[m.face_vertices[off[f] + (k + 1) % n]];
    sum += std::sqrt(double(a[0] - b[0]) * (a[0] - b[0]) + double(a[1] - b[1]) * (a[1] - b[1]) +
                     double(a[2] - b[2]) * (a[2] - b[2]));
  }
  return sum / n;
}

// The base vertex at the ptex corner a coord lies on, or -1: a quad's (Catmull-Clark) or a
// triangle's (Loop) corners are its vertices in order; an n-gon's sub-face k has vertex k at (0, 0).
int corner_vertex(const ControlMesh& m, const std::vector<int>& off, SubdivisionRule rule, int f, int sub, double u,
                  double v) {
  auto at = [&](int k) { return m.face_vertices[off[f] + k]; };
  if (rule == SubdivisionRule::Loop) return u == 0 && v == 0 ? at(0) : u == 1 && v == 0 ? at(1) : u == 0 && v == 1 ? at(2) : -1;
  if (m.face_sizes[f] != 4) return u == 0 && v == 0 ? at(sub) : -1;
  if (u != 0 && u != 1) return -1;
  if (v != 0 && v != 1) return -1;
  return at(v == 0 ? (u == 0 ? 0 : 1) : (u == 1 ? 2 : 3));
}

Point3d cross3(const Point3d& a, const Point3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm3(const Point3d& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

// Bfr at (u, v) of its face's parametrization; the normal zero where it degenerates.
void evaluate_surface(const Bfr::Surface<double>& s, const double* patch, UV uv, Point3d& p, Point3d& du, Point3d& dv,
                      Point3d& n) {
  s.Evaluate(uv.data(), patch, 3, p.data(), du.data(), dv.data());
  n = tangents_degenerate(du.data(), dv.data()) ? Point3d{0, 0, 0} : cross3(du, dv);
}

Point3d unit3(const Point3d& n) {
  const double len = norm3(n);
  return len > 0 ? Point3d{n[0] / len, n[1] / len, n[2] / len} : Point3d{0, 0, 0};
}

std::vector<double> prepared_patch(const Bfr::Surface<double>& s, const std::vector<Point3d>& points) {
  std::vector<double> patch(3 * s.GetNumPatchPoints());
  s.PreparePatchPoints(points[0].data(), 3, patch.data(), 3);
  return patch;
}

Bfr::RefinerSurfaceFactory<>::Options bfr_options(const LimitAccuracy& accuracy) {
  Bfr::RefinerSurfaceFactory<>::Options options;
  options.SetApproxLevelSmooth(accuracy.smooth);
  options.SetApproxLevelSharp(accuracy.sharp);
  return options;
}

// Two edges between the same two vertices, in the mesh or in Far's first two levels of it: faces
// folded onto each other (a face repeating a vertex, or two faces sharing more than one edge,
// whose children then do). Local refinement, the exact limit where Bfr is not (vertex_limit.h),
// cuts faces out by their vertex lists and would merge such edges: the yardstick refuses these
// meshes (catmark_nonman_edges and the non-manifold quad poles at level 0, loop_val2_interior at
// level 1), naming the face.
std::optional<std::string> folded_faces(const ControlMesh& mesh, SubdivisionRule rule) {
  auto doubled = [](const Far::TopologyLevel& l) {
    for (int v = 0; v < l.GetNumVertices(); ++v) {
      std::vector<int> ends;
      for (int e : l.GetVertexEdges(v)) {
        Far::ConstIndexArray ev = l.GetEdgeVertices(e);
        ends.push_back(ev[0] == v ? ev[1] : ev[0]);
      }
      std::sort(ends.begin(), ends.end());
      if (std::adjacent_find(ends.begin(), ends.end()) != ends.end()) return v;
    }
    return -1;
  };
  auto refiner = make_refiner(mesh, rule);
  const Far::TopologyLevel& l0 = refiner->GetLevel(0);
  bool shared_twice = false;  // faces that share more than one edge: the children may fold
  for (int e = 0; e < l0.GetNumEdges() && !shared_twice; ++e)
    for (int f : l0.GetEdgeFaces(e))
      for (int g : l0.GetEdgeFaces(e))
        if (f < g) {
          int common = 0;
          for (int a : l0.GetFaceEdges(f))
            for (int b : l0.GetFaceEdges(g)) common += a == b;
          shared_twice |= common > 1;
        }
  int level = doubled(l0) >= 0 ? 0 : -1;
  if (level < 0 && shared_twice) {
    Far::TopologyRefiner::UniformOptions options(2);
    options.fullTopologyInLastLevel = true;
    refiner->RefineUniform(options);
    for (int l = 1; l <= 2 && level < 0; ++l)
      if (doubled(refiner->GetLevel(l)) >= 0) level = l;
  }
  if (level < 0) return std::nullopt;
  return mesh.source + ": faces folded onto each other (two edges between the same two vertices at level " +
         std::to_string(level) + "): the exact limit's local refinement cannot cut them out, so no deviation here";
}

}  // namespace

// Bfr (OpenSubdiv 3.5.0) is the limit everywhere but where the probes against Far's refinement
// found it off (limit_evaluator.h): next to a non-manifold corner or edge (up to 2% of the
// diagonal, catmark_nonman_edges), next to an interior vertex of valence 2 (0.92%, the
// quadrangulated catmark_val2_foldover), next to a corner whose Chaikin creases are still semi-sharp
// (0.067% and 6.7 degrees, loop_chaikin1), and the faces it builds from uninitialised memory
// (bfr_defect.h). A face is trusted when none of its corners has such a neighbourhood.
bool LimitEvaluator::Impl::face_trusted(const Far::TopologyLevel& l, int f, const std::vector<char>& marks) const {
  const bool chaikin = mesh.crease_method == CreaseMethod::Chaikin;
  for (int a : l.GetFaceVertices(f)) {
    if (chaikin && l.IsVertexSemiSharp(a)) return false;
    for (int e : l.GetVertexEdges(a))
      if (chaikin && l.IsEdgeSemiSharp(e)) return false;
    // Non-manifold: anywhere in the faces around the corners (Bfr was measured off a ring out).
    for (int g : l.GetVertexFaces(a))
      for (int b : l.GetFaceVertices(g))
        if (marks[b]) return false;
  }
  return true;
}

const VertexLimit& LimitEvaluator::Impl::vertex(int v) const {
  std::call_once(vertex_once[v], [&] {
    vertex_limits[v] = vertex_limit(refiner->GetLevel(0), refiner->GetSchemeOptions(), rule, points, v);
  });
  return vertex_limits[v];
}

std::shared_ptr<const Node> LimitEvaluator::Impl::make_node(const Far::TopologyLevel& l, const std::vector<Point3d>& pts,
                                                            const std::vector<char>& level_marks, int face,
                                                            std::vector<UV> corner_uv, int level) const {
  auto node = std::make_shared<Node>();
  node->mesh = cut_faces(l, pts, faces_around(l, face), nullptr, &level_marks);
  node->corner_uv = std::move(corner_uv);
  node->level = level;
  auto r = refiner_of(node->mesh, rule, refiner->GetSchemeOptions());
  for (int a : l.GetFaceVertices(face)) {  // as vertex_limit's ring: two edges to one neighbour
    std::vector<int> ends;
    for (int e : l.GetVertexEdges(a)) {
      Far::ConstIndexArray ev = l.GetEdgeVertices(e);
      ends.push_back(ev[0] == a ? ev[1] : ev[0]);
    }
    std::sort(ends.begin(), ends.end());
    if (std::adjacent_find(ends.begin(), ends.end()) != ends.end())
      throw Unsupported("LimitEvaluator: a corner with two edges to one neighbour (faces folded onto each other) next "
                        "to a face Bfr does not evaluate exactly: no local refinement there");
  }
  node->trusted = face_trusted(r->GetLevel(0), 0, node->mesh.marks);
  ControlMesh cut;  // for the defect test, which reads a ControlMesh
  cut.face_sizes = node->mesh.face_sizes, cut.face_vertices = node->mesh.face_vertices;
  cut.positions.resize(node->mesh.points.size());
  for (size_t i = 0; i + 1 < node->mesh.crease_pairs.size(); i += 2)
    cut.creases.push_back({node->mesh.crease_pairs[i], node->mesh.crease_pairs[i + 1], node->mesh.crease_weights[i / 2]});
  const bool defect = bfr_defect_faces(cut)[0];
  node->trusted = node->trusted && !defect;
  if (!defect && (node->trusted || level >= 12)) {
    const Bfr::RefinerSurfaceFactory<> factory(*r, bfr_options(accuracy));
    if (factory.InitVertexSurface(0, &node->surface)) node->patch_points = prepared_patch(node->surface, node->mesh.points);
    node->trusted = node->trusted && node->surface.IsValid();
  }
  return node;
}

std::shared_ptr<const Node> LimitEvaluator::Impl::root(int f, int sub) const {
  const std::vector<long> key = {f, sub, -1};
  {
    std::lock_guard<std::mutex> lock(nodes_mutex);
    if (auto it = nodes.find(key); it != nodes.end()) return it->second;
  }
  const Far::TopologyLevel& l0 = refiner->GetLevel(0);
  const int n = mesh.face_sizes[f];
  std::shared_ptr<const Node> node;
  if (rule == SubdivisionRule::Loop) {
    node = make_node(l0, points, marks, f, {{0, 0}, {1, 0}, {0, 1}}, 0);
  } else if (n == 4) {
    node = make_node(l0, points, marks, f, {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 0);
  } else {
    // An n-gon's ptex face `sub` is its child at corner `sub`: corner (0, 0), the next edge's
    // point (1, 0), the centre (1, 1), the previous edge's point (0, 1).
    const Node top = *make_node(l0, points, marks, f, std::vector<UV>(n, UV{0, 0}), 0);
    auto r = refiner_of(top.mesh, rule, refiner->GetSchemeOptions());
    const std::vector<Point3d> next = refine_once(*r, top.mesh.points);
    const std::vector<char> next_marks = refine_marks(*r, top.mesh.marks);
    const Far::TopologyLevel &p = r->GetLevel(0), &c = r->GetLevel(1);
    Far::ConstIndexArray fv = p.GetFaceVertices(0), fe = p.GetFaceEdges(0);
    for (int child : p.GetFaceChildFaces(0)) {
      Far::ConstIndexArray cv = c.GetFaceVertices(child);
      std::vector<UV> uv(cv.size());
      bool ours = false;
      for (int j = 0; j < cv.size(); ++j) {
        if (cv[j] == p.GetVertexChildVertex(fv[sub])) uv[j] = {0, 0}, ours = true;
        else if (cv[j] == p.GetEdgeChildVertex(fe[sub])) uv[j] = {1, 0};
        else if (cv[j] == p.GetFaceChildVertex(0)) uv[j] = {1, 1};
        else uv[j] = {0, 1};
      }
      if (ours) node = make_node(c, next, next_marks, child, uv, 1);
    }
  }
  std::lock_guard<std::mutex> lock(nodes_mutex);
  return nodes.emplace(key, node).first->second;
}

namespace {

bool inside(const std::vector<UV>& c, UV p) {
  const double tol = 1e-12;
  if (c.size() == 3) {  // barycentric, in the ptex triangle
    const double ax = c[1][0] - c[0][0], ay = c[1][1] - c[0][1], bx = c[2][0] - c[0][0], by = c[2][1] - c[0][1];
    const double det = ax * by - ay * bx, px = p[0] - c[0][0], py = p[1] - c[0][1];
    const double s = (px * by - py * bx) / det, t = (ax * py - ay * px) / det;
    return s >= -tol && t >= -tol && s + t <= 1 + tol;
  }
  double lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9};
  for (const UV& q : c)
    for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], q[k]), hi[k] = std::max(hi[k], q[k]);
  return p[0] >= lo[0] - tol && p[0] <= hi[0] + tol && p[1] >= lo[1] - tol && p[1] <= hi[1] + tol;
}

UV mid(UV a, UV b) { return {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])}; }

// (u, v) in the focus's own parametrization: corner 0 at (0, 0), corner 1 at (1, 0), the last at
// (0, 1); `ds`, `dt` its axes in ptex units.
UV local_uv(const std::vector<UV>& c, UV p, UV& ds, UV& dt) {
  ds = {c[1][0] - c[0][0], c[1][1] - c[0][1]};
  dt = {c.back()[0] - c[0][0], c.back()[1] - c[0][1]};
  const double det = ds[0] * dt[1] - ds[1] * dt[0], px = p[0] - c[0][0], py = p[1] - c[0][1];
  return {(px * dt[1] - py * dt[0]) / det, (ds[0] * py - ds[1] * px) / det};
}

}  // namespace

std::shared_ptr<const Node> LimitEvaluator::Impl::child(const Node& parent, UV uv) const {
  auto r = refiner_of(parent.mesh, rule, refiner->GetSchemeOptions());
  const std::vector<Point3d> next = refine_once(*r, parent.mesh.points);
  const std::vector<char> next_marks = refine_marks(*r, parent.mesh.marks);
  const Far::TopologyLevel &p = r->GetLevel(0), &c = r->GetLevel(1);
  Far::ConstIndexArray fv = p.GetFaceVertices(0), fe = p.GetFaceEdges(0);
  const int n = fv.size();
  UV centre = {0, 0};
  for (const UV& q : parent.corner_uv) centre[0] += q[0] / n, centre[1] += q[1] / n;
  const int face_point = rule == SubdivisionRule::Loop ? -1 : p.GetFaceChildVertex(0);
  Far::ConstIndexArray children = p.GetFaceChildFaces(0);
  for (int i = 0; i < children.size(); ++i) {
    // Far orders a face's children by its corners (Loop's last child is the middle one); a face
    // that repeats a vertex (non-manifold input) is told apart by that order alone.
    Far::ConstIndexArray cv = c.GetFaceVertices(children[i]);
    std::vector<UV> corners(cv.size());
    for (int j = 0; j < cv.size(); ++j) {
      if (cv[j] == face_point) corners[j] = centre;
      bool found = false;
      for (int step = 0; step < n && !found; ++step) {  // corner i's own elements first
        const int k = (i + step) % n;
        if (i < n && cv[j] == p.GetVertexChildVertex(fv[k])) corners[j] = parent.corner_uv[k], found = true;
        else if (cv[j] == p.GetEdgeChildVertex(fe[k])) corners[j] = mid(parent.corner_uv[k], parent.corner_uv[(k + 1) % n]), found = true;
        else if (cv[j] == p.GetEdgeChildVertex(fe[(k + n - 1) % n]))
          corners[j] = mid(parent.corner_uv[(k + n - 1) % n], parent.corner_uv[k]), found = true;
      }
    }
    if (inside(corners, uv)) return make_node(c, next, next_marks, children[i], corners, parent.level + 1);
  }
  std::string where;
  for (const UV& q : parent.corner_uv) where += " (" + std::to_string(q[0]) + "," + std::to_string(q[1]) + ")";
  throw std::logic_error("LimitEvaluator: a point (" + std::to_string(uv[0]) + "," + std::to_string(uv[1]) + ") in no child of its face at level " + std::to_string(parent.level) + where);
}

// Down the face's children until the point is one of their corners (the vertex's exact limit),
// or Bfr is exact on the child, or 12 levels deep.
LimitSample LimitEvaluator::Impl::descend(int f, int sub, UV uv) const {
  std::shared_ptr<const Node> node = root(f, sub);
  constexpr int kMaxLevel = 12;
  for (;;) {
    const Node& at = *node;
    LimitSample out;
    for (size_t j = 0; j < at.corner_uv.size(); ++j) {
      if (std::abs(at.corner_uv[j][0] - uv[0]) > 1e-12 || std::abs(at.corner_uv[j][1] - uv[1]) > 1e-12) continue;
      auto r = refiner_of(at.mesh, rule, refiner->GetSchemeOptions());
      const int v = r->GetLevel(0).GetFaceVertices(0)[j];
      const VertexLimit limit = vertex_limit(r->GetLevel(0), refiner->GetSchemeOptions(), rule, at.mesh.points, v);
      Far::ConstIndexArray vf = r->GetLevel(0).GetVertexFaces(v);
      const int slot = static_cast<int>(std::find(vf.begin(), vf.end(), 0) - vf.begin());
      out.position = limit.position;
      out.normal = limit.normal[slot];
      return out;
    }
    if (at.trusted || at.level >= kMaxLevel) {
      // 12 levels in, a point no child has at a corner takes Bfr on the child even where Bfr is
      // off: its error shrinks with the child, 2^-12 of the face.
      UV ds, dt;
      const UV st = local_uv(at.corner_uv, uv, ds, dt);
      Point3d a, b, n;
      if (!at.surface.IsValid()) throw Unsupported("LimitEvaluator: no limit surface 12 levels into face " + std::to_string(f));
      evaluate_surface(at.surface, at.patch_points.data(), st, out.position, a, b, n);
      // d/du and d/dv from d/ds and d/dt: (s, t) = A^-1 (u, v) with A's columns ds, dt.
      const double det = ds[0] * dt[1] - ds[1] * dt[0];
      for (int k = 0; k < 3; ++k) {
        out.du[k] = (a[k] * dt[1] - b[k] * ds[1]) / det;
        out.dv[k] = (b[k] * ds[0] - a[k] * dt[0]) / det;
      }
      out.normal = unit3(det > 0 ? n : Point3d{-n[0], -n[1], -n[2]});
      return out;
    }
    std::vector<long> key = {f, sub, at.level + 1};
    std::shared_ptr<const Node> next = child(at, uv);
    for (const UV& q : next->corner_uv)
      key.push_back(std::lround(q[0] * (1L << 20))), key.push_back(std::lround(q[1] * (1L << 20)));
    std::lock_guard<std::mutex> lock(nodes_mutex);
    node = nodes.emplace(key, next).first->second;
  }
}

LimitEvaluator::LimitEvaluator(const ControlMesh& mesh, SubdivisionRule rule, LimitAccuracy accuracy)
    : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  d.mesh = mesh;
  d.rule = rule;
  d.accuracy = accuracy;
  d.refiner = make_refiner(mesh, rule);
  const Far::PtexIndices ptex(*d.refiner);
  const int nf = num_faces(mesh);
  const int regular = rule == SubdivisionRule::Loop ? 3 : 4;
  d.first_ptex.resize(nf);
  if (auto folded = folded_faces(mesh, rule)) throw Unsupported(*folded);
  for (int f = 0; f < nf; ++f) {
    d.first_ptex[f] = ptex.GetFaceId(f);
    const int subfaces = mesh.face_sizes[f] == regular ? 1 : mesh.face_sizes[f];
    if (rule == SubdivisionRule::Loop && mesh.face_sizes[f] != 3)
      throw InputError(face_location(mesh, f), "Loop subdivision needs triangles, face has " +
                                                   std::to_string(mesh.face_sizes[f]) + " vertices");
    for (int k = 0; k < subfaces; ++k) {
      d.ptex_base.push_back(f);
      d.ptex_sub.push_back(k);
    }
  }
  const Bfr::RefinerSurfaceFactory<> factory(*d.refiner, bfr_options(accuracy));
  d.points.resize(mesh.positions.size());
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    for (int k = 0; k < 3; ++k) d.points[v][k] = mesh.positions[v][k];
  d.vertex_once = std::make_unique<std::once_flag[]>(mesh.positions.size());
  d.vertex_limits.resize(mesh.positions.size());
  d.offsets = face_offsets(mesh);
  d.surfaces.resize(nf);
  d.patch_points.resize(nf);
  d.local_size.resize(nf);
  d.has_limit.resize(nf);
  d.trusted.resize(nf);
  const std::vector<char> defect = bfr_defect_faces(mesh);
  const Far::TopologyLevel& l0 = d.refiner->GetLevel(0);
  d.marks.assign(mesh.positions.size(), 0);
  for (int v = 0; v < l0.GetNumVertices(); ++v) {
    d.marks[v] |= l0.IsVertexNonManifold(v);
    d.marks[v] |= !l0.IsVertexBoundary(v) && l0.GetVertexEdges(v).size() == 2;  // an interior valence 2
    for (int e : l0.GetVertexEdges(v)) d.marks[v] |= l0.IsEdgeNonManifold(e) || l0.GetEdgeFaces(e).size() > 2;
  }
  for (int f = 0; f < nf; ++f) {
    d.local_size[f] = mean_edge_length(mesh, d.offsets, f);
    d.has_limit[f] = factory.FaceHasLimitSurface(f);
    d.trusted[f] = d.has_limit[f] && !defect[f] && d.face_trusted(l0, f, d.marks);
    if (!d.trusted[f]) continue;
    factory.InitVertexSurface(f, &d.surfaces[f]);
    d.patch_points[f] = prepared_patch(d.surfaces[f], d.points);
  }
}

LimitEvaluator::~LimitEvaluator() = default;

int LimitEvaluator::num_ptex_faces() const { return static_cast<int>(impl_->ptex_base.size()); }

std::pair<int, int> LimitEvaluator::base_face(int ptex_face) const {
  return {impl_->ptex_base.at(ptex_face), impl_->ptex_sub.at(ptex_face)};
}

int LimitEvaluator::first_ptex_face(int base_face) const { return impl_->first_ptex.at(base_face); }

bool LimitEvaluator::has_limit(int ptex_face) const { return impl_->has_limit.at(impl_->ptex_base.at(ptex_face)); }

LimitSample LimitEvaluator::evaluate(SurfaceCoord c) const {
  const Impl& d = *impl_;
  if (c.face >= d.ptex_base.size()) throw std::out_of_range("LimitEvaluator: ptex face out of range");
  const int f = d.ptex_base[c.face], sub = d.ptex_sub[c.face];
  if (!d.has_limit[f]) throw std::invalid_argument("LimitEvaluator: face " + std::to_string(f) + " has no limit surface");
  const int corner = corner_vertex(d.mesh, d.offsets, d.rule, f, sub, c.u, c.v);
  LimitSample out;
  if (!d.trusted[f]) {
    out = d.descend(f, sub, {c.u, c.v});
  } else {
    const Bfr::Surface<double>& s = d.surfaces[f];
    UV uv = {c.u, c.v};
    const Bfr::Parameterization param = s.GetParameterization();
    double scale = 1.0;  // d(face coord) / d(ptex coord)
    if (param.HasSubFaces()) {
      // Normalized sub-face coordinates are Ptex coordinates (Bfr::Parameterization docs); a
      // sub-face spans half a unit of the face's tiled (u,v), hence the derivative scale.
      const double sub_uv[2] = {c.u, c.v};
      param.ConvertNormalizedSubFaceToCoord(sub, sub_uv, uv.data());
      scale = 0.5;
    }
    Point3d du, dv, n;
    evaluate_surface(s, d.patch_points[f].data(), uv, out.position, du, dv, n);
    for (int k = 0; k < 3; ++k) out.du[k] = du[k] * scale, out.dv[k] = dv[k] * scale;
    out.normal = unit3(n);
  }
  if (corner >= 0) {  // a base vertex: its exact limit, on this face's side
    const VertexLimit& limit = d.vertex(corner);
    Far::ConstIndexArray vf = d.refiner->GetLevel(0).GetVertexFaces(corner);
    const int slot = static_cast<int>(std::find(vf.begin(), vf.end(), f) - vf.begin());
    out.position = limit.position;
    if (slot < vf.size()) out.normal = limit.normal[slot];  // zero where the surface has none
    if (norm3(out.normal) > 0.5) {
      // The normals inside the face, 1e-3 towards its centre, must lead to it: where they point
      // the other way (a face folded over its neighbour: catmark_val2_back2back quadrangulated)
      // the corner has no one-sided normal.
      const double step = 1e-3, mid = d.rule == SubdivisionRule::Loop ? 1.0 / 3 : 0.5;
      const LimitSample inside =
          evaluate({c.face, float(c.u + step * (mid - c.u)), float(c.v + step * (mid - c.v))});
      const double agree = out.normal[0] * inside.normal[0] + out.normal[1] * inside.normal[1] + out.normal[2] * inside.normal[2];
      if (agree < 0) out.normal = {0, 0, 0};
    }
  }
  return out;
}

double LimitEvaluator::local_size(int ptex_face) const { return impl_->local_size.at(impl_->ptex_base.at(ptex_face)); }

const ControlMesh& LimitEvaluator::mesh() const { return impl_->mesh; }

SubdivisionRule LimitEvaluator::rule() const { return impl_->rule; }

}  // namespace sdb
