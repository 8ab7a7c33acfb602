#include "harness/reference/vertex_limit.h"

#include <opensubdiv/far/primvarRefiner.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "harness/core/errors.h"
#include "harness/mesh/osd_topology.h"
#include "harness/reference/local_mesh.h"
#include "harness/reference/ring_limit.h"

namespace sdb {
namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

// The faces around one vertex as a mesh of their own; each face remembers which face of the
// original vertex it descends from (its side).
struct Ring {
  LocalMesh mesh;
  int centre = 0;         // the vertex, in the cut-out's numbering
  std::vector<int> side;  // per local face
};

Ring ring_of(const Far::TopologyLevel& l, const std::vector<Point3d>& points, int v, const std::vector<int>& side) {
  Far::ConstIndexArray vf = l.GetVertexFaces(v);
  std::vector<int> local;
  Ring r{cut_faces(l, points, {vf.begin(), vf.end()}, &local), 0, side};
  r.centre = local[v];
  // Far may hold two edges between the same two vertices (faces folded onto each other, children
  // of different parents); a cut-out, made from face lists, merges them and changes the vertex.
  std::vector<int> ends;
  for (int e : l.GetVertexEdges(v)) {
    Far::ConstIndexArray ev = l.GetEdgeVertices(e);
    ends.push_back(ev[0] == v ? ev[1] : ev[0]);
  }
  std::sort(ends.begin(), ends.end());
  if (std::adjacent_find(ends.begin(), ends.end()) != ends.end())
    throw Unsupported("a vertex with two edges to one neighbour (faces folded onto each other): its limit needs the "
                      "whole mesh refined, which the local refinement does not do");
  return r;
}

Point3d cross(const Point3d& a, const Point3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

Point3d unit(const Point3d& n) {
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(len > 0)) return {0, 0, 0};
  return {n[0] / len, n[1] / len, n[2] / len};
}

Point3d apply(const std::vector<double>& w, const std::vector<int>& ring, const std::vector<Point3d>& points) {
  Point3d s{0, 0, 0};
  for (size_t i = 0; i < w.size(); ++i)
    for (int k = 0; k < 3; ++k) s[k] += w[i] * points[ring[i]][k];
  return s;
}

// A point as PrimvarRefinerReal<double> interpolates it: double weights on double coordinates.
struct DoublePoint {
  double p[3];
  void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0; }
  void AddWithWeight(const DoublePoint& s, double w) {
    p[0] += w * s.p[0];
    p[1] += w * s.p[1];
    p[2] += w * s.p[2];
  }
};

Point3d sub(const Point3d& a, const Point3d& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

bool smooth_interior(const Far::TopologyLevel& l, int v) {
  if (l.IsVertexBoundary(v) || l.IsVertexNonManifold(v) || l.GetVertexSharpness(v) > 0) return false;
  for (int e : l.GetVertexEdges(v))
    if (l.GetEdgeSharpness(e) > 0) return false;
  return l.GetVertexEdges(v).size() >= 3;
}

Ring refined(const Ring& ring, SubdivisionRule rule, const Sdc::Options& options);

// Each side's corner at the centre refined `levels` further: the normal of the face's corner
// (next edge x previous edge), which tends to that side's limit normal where there is one. Orients
// the eigenvectors' normals, whose sign the eigen-analysis alone leaves in doubt at special
// vertices (a valence-2 neighbour turns the ring over).
std::vector<Point3d> corner_normals(const Ring& ring, SubdivisionRule rule, const Sdc::Options& options, int sides) {
  std::vector<Point3d> out(sides, Point3d{0, 0, 0});
  auto r = refiner_of(ring.mesh, rule, options);
  const Far::TopologyLevel& l = r->GetLevel(0);
  const std::vector<Point3d>& p = ring.mesh.points;
  Far::ConstIndexArray vf = l.GetVertexFaces(ring.centre);
  for (int k = 0; k < vf.size(); ++k) {
    Far::ConstIndexArray fv = l.GetFaceVertices(vf[k]);
    const int i = l.GetVertexFaceLocalIndices(ring.centre)[k], m = fv.size();
    out[ring.side[vf[k]]] = unit(cross(sub(p[fv[(i + 1) % m]], p[ring.centre]), sub(p[fv[(i + m - 1) % m]], p[ring.centre])));
  }
  return out;
}

// The same `levels` and `levels + 1` further down.
std::pair<std::vector<Point3d>, std::vector<Point3d>> sector_normals(Ring ring, SubdivisionRule rule,
                                                                     const Sdc::Options& options, int sides, int levels) {
  for (int k = 0; k < levels; ++k) ring = refined(ring, rule, options);
  std::vector<Point3d> at = corner_normals(ring, rule, options, sides);
  return {at, corner_normals(refined(ring, rule, options), rule, options, sides)};
}

double dot(const Point3d& a, const Point3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Far makes a non-manifold vertex an infinitely sharp corner: a face's side there is bounded by
// its two edges at the vertex, and where both are infinitely sharp (the ends of two crease
// curves) their directions are the limit's tangents. Elsewhere no normal is claimed: the
// eigenvectors of the face's fan alone missed the one-sided limit by 6.6 degrees on
// catmark_val2_nonman's non-manifold edge.
Point3d corner_normal(const Far::TopologyLevel& l, const std::vector<Point3d>& points, int c, int k) {
  const int f = l.GetVertexFaces(c)[k];
  Far::ConstIndexArray fv = l.GetFaceVertices(f), fe = l.GetFaceEdges(f);
  const int i = l.GetVertexFaceLocalIndices(c)[k], m = fv.size();
  if (!l.IsEdgeInfSharp(fe[i]) || !l.IsEdgeInfSharp(fe[(i + m - 1) % m])) return {0, 0, 0};
  return unit(cross(sub(points[fv[(i + 1) % m]], points[c]), sub(points[fv[(i + m - 1) % m]], points[c])));
}

// The limit at the ring's centre, whose rules repeat from here on.
VertexLimit limit_of(const Ring& ring, const Far::TopologyRefiner& r, SubdivisionRule rule, const Sdc::Options& options,
                     int sides) {
  const Far::TopologyLevel& l = r.GetLevel(0);
  const bool catmark = rule == SubdivisionRule::CatmullClark;
  const int c = ring.centre;
  const std::vector<Point3d>& points = ring.mesh.points;
  VertexLimit out;
  out.normal.assign(sides, Point3d{0, 0, 0});
  std::vector<DoublePoint> src(points.size()), pos(points.size()), t1(points.size()), t2(points.size());
  for (size_t i = 0; i < points.size(); ++i) src[i] = {{points[i][0], points[i][1], points[i][2]}};
  DoublePoint *p = pos.data(), *a = t1.data(), *b = t2.data();
  Far::PrimvarRefinerReal<double>(r).Limit(src.data(), p, a, b);
  out.position = {pos[c].p[0], pos[c].p[1], pos[c].p[2]};
  Far::ConstIndexArray ve = l.GetVertexEdges(c), vf = l.GetVertexFaces(c);
  const Sdc::Crease::Rule vertex_rule = l.GetVertexRule(c);
  const bool manifold = !l.IsVertexNonManifold(c);
  // Far's position masks are the limit everywhere but at darts and smooth valence-2 vertices.
  int sharp = -1;
  for (int i = 0; i < ve.size(); ++i)
    if (l.GetEdgeSharpness(ve[i]) > 0) sharp = i;
  const bool dart = vertex_rule == Sdc::Crease::RULE_DART && !l.IsVertexBoundary(c);
  const bool valence2 = vertex_rule == Sdc::Crease::RULE_SMOOTH && !l.IsVertexBoundary(c) && ve.size() == 2;
  if ((dart || valence2) && manifold) {
    const int start = dart ? sharp : 0;
    out.position = apply(ring_limit_weights(l, options, catmark, c, start), ring_limit_vertices(l, c, catmark, start), points);
  }
  // No normal at a smooth vertex of valence 2: the surface has no tangent plane there. Its
  // subdominant eigenvalues come in a pair of opposite signs, the refined ring turns over at
  // every level, and the limit's normals along a line into the vertex swing by 12 degrees
  // without converging (catmark_val2_interior, 2^-3 .. 2^-11 from it).
  if (valence2 && manifold) return out;
  if (smooth_interior(l, c)) {  // one tangent plane, and Far's tangent masks are its eigenvectors
    const Point3d a1 = {t1[c].p[0], t1[c].p[1], t1[c].p[2]}, a2 = {t2[c].p[0], t2[c].p[1], t2[c].p[2]};
    const double scale = std::max(dot(a1, a1), dot(a2, a2));
    const Point3d n = unit(cross(a1, a2));
    if (dot(cross(a1, a2), cross(a1, a2)) > 1e-20 * scale * scale) {
      for (int k = 0; k < vf.size(); ++k) out.normal[ring.side[vf[k]]] = n;
      return out;
    }
    // Its tangents vanish: a ring folded flat onto itself (catmark_val2_back2back), whose faces'
    // corners point either way: no tangent plane.
    return out;
  }
  // One side only (a boundary or a corner of one face, no sharp edge between its faces) where
  // Far's masks are the limit: theirs (oriented as the limit's du x dv, not as the control
  // polygon, which a fold turns over: catmark_val2_foldover).
  int inner_sharp = 0;
  for (int e : ve) inner_sharp += l.GetEdgeSharpness(e) > 0 && l.GetEdgeFaces(e).size() == 2;
  if (manifold && inner_sharp == 0 && (vf.size() == 1 || l.GetVertexSharpness(c) <= 0) &&
      far_tangent_masks_exact(l, c, rule)) {
    const Point3d n = unit(cross({t1[c].p[0], t1[c].p[1], t1[c].p[2]}, {t2[c].p[0], t2[c].p[1], t2[c].p[2]}));
    for (int k = 0; k < vf.size(); ++k) out.normal[ring.side[vf[k]]] = n;
    return out;
  }
  const std::vector<int> order = ring_limit_vertices(l, c, catmark, 0);
  for (int k = 0; k < vf.size(); ++k) {
    Point3d n{0, 0, 0};
    if (manifold) {
      const RingTangents t = ring_limit_tangents(l, options, catmark, c, k);
      if (!t.first.empty()) n = unit(cross(apply(t.first, order, points), apply(t.second, order, points)));
    } else {
      n = corner_normal(l, points, c, k);
    }
    out.normal[ring.side[vf[k]]] = n;
  }
  bool missing = false;
  for (const Point3d& n : out.normal) missing |= dot(n, n) < 0.25;
  if (!missing && far_tangent_masks_exact(l, c, rule)) return out;  // regular creases, corners of one face
  // A ring that turns over from one level to the next (the normals of its faces' corners flip)
  // gives the surface no orientation at the vertex: no normal there.
  const auto [sector, next] = sector_normals(ring, rule, options, sides, 12);
  for (int k = 0; k < sides; ++k) {
    if (dot(sector[k], next[k]) < 0) out.normal[k] = {0, 0, 0};
    else if (dot(out.normal[k], sector[k]) < 0) out.normal[k] = {-out.normal[k][0], -out.normal[k][1], -out.normal[k][2]};
  }
  return out;
}

bool all_quads(const Far::TopologyLevel& l, int v) {
  for (int f : l.GetVertexFaces(v))
    if (l.GetFaceVertices(f).size() != 4) return false;
  return true;
}

Ring refined(const Ring& ring, SubdivisionRule rule, const Sdc::Options& options) {
  auto r = refiner_of(ring.mesh, rule, options);
  const std::vector<Point3d> next = refine_once(*r, ring.mesh.points);
  const Far::TopologyLevel& l1 = r->GetLevel(1);
  const int child = r->GetLevel(0).GetVertexChildVertex(ring.centre);
  Far::ConstIndexArray cf = l1.GetVertexFaces(child);
  std::vector<int> side(cf.size());
  for (int k = 0; k < cf.size(); ++k) side[k] = ring.side[l1.GetFaceParentFace(cf[k])];
  return ring_of(l1, next, child, side);
}

}  // namespace

bool vertex_sharpness_decays(const Far::TopologyLevel& l, int v) {
  if (l.IsVertexSemiSharp(v)) return true;
  for (int e : l.GetVertexEdges(v))
    if (l.IsEdgeSemiSharp(e)) return true;
  return false;
}

VertexLimit vertex_limit(const Far::TopologyLevel& level, const Sdc::Options& options, SubdivisionRule rule,
                         const std::vector<Point3d>& points, int v, int extra_levels) {
  const int sides = level.GetVertexFaces(v).size();
  std::vector<int> identity(sides);
  for (int k = 0; k < sides; ++k) identity[k] = k;
  Ring ring = ring_of(level, points, v, identity);
  const bool catmark = rule == SubdivisionRule::CatmullClark;
  int levels = 0, extra = extra_levels;
  for (;;) {
    auto r = refiner_of(ring.mesh, rule, options);
    const Far::TopologyLevel& l0 = r->GetLevel(0);
    // Sdc's ring matrix reads quads (Catmull-Clark), and each point of the ring once: an n-gon's
    // vertex, or one whose faces meet again beyond it (a valence-2 neighbour), is refined first.
    std::vector<int> order = ring_limit_vertices(l0, ring.centre, catmark, 0);
    std::sort(order.begin(), order.end());
    const bool repeats = std::adjacent_find(order.begin(), order.end()) != order.end();
    const bool decays =
        vertex_sharpness_decays(l0, ring.centre) || (catmark && !all_quads(l0, ring.centre)) || (repeats && levels < 4);
    if (!decays && extra == 0) {
      VertexLimit out = limit_of(ring, *r, rule, options, sides);
      out.levels = levels;
      return out;
    }
    if (!decays) --extra;
    if (levels > 12 + extra_levels) throw std::logic_error("vertex_limit: sharpness that does not decay");
    ring = refined(ring, rule, options);
    ++levels;
  }
}

}  // namespace sdb
