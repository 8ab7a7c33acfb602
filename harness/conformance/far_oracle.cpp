#include "harness/conformance/far_oracle.h"

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyRefiner.h>

#include <algorithm>
#include <cmath>

#include "harness/mesh/osd_topology.h"
#include "harness/reference/surface_normal.h"
#include "harness/reference/uniform_coords.h"

namespace sdb::conformance {

namespace Far = OpenSubdiv::Far;

GridKey grid_key(const SurfaceCoord& c, int depth) {
  const float s = static_cast<float>(1 << depth);
  return {c.face, static_cast<int>(std::lround(c.u * s)), static_cast<int>(std::lround(c.v * s))};
}

bool far_limit_is_exact(const Far::TopologyLevel& l, int v, SubdivisionRule rule) {
  // Sharpness left at the last level: Far's masks take it as infinite.
  if (l.IsVertexSemiSharp(v)) return false;
  for (int e : l.GetVertexEdges(v))
    if (l.IsEdgeSemiSharp(e)) return false;
  return far_tangent_masks_exact(l, v, rule);
}


// Far's rules, accumulated in double: the oracle's own rounding stays far below the 1e-6 the
// float fragments are held to (on a valence-360 pole a float oracle alone is off by 1e-6).
using DoublePoint = PrimvarPointT<double>;

FarLevel far_level(const ControlMesh& m, SubdivisionRule rule, int depth, bool limit) {
  auto r = make_refiner(m, rule);
  Far::TopologyRefiner::UniformOptions options(depth);
  options.fullTopologyInLastLevel = true;
  r->RefineUniform(options);
  std::vector<std::vector<DoublePoint>> levels(depth + 1);
  for (int l = 0; l <= depth; ++l) levels[l].resize(r->GetLevel(l).GetNumVertices());
  for (size_t v = 0; v < m.positions.size(); ++v)
    for (int k = 0; k < 3; ++k) levels[0][v].p[k] = m.positions[v][k];
  Far::PrimvarRefiner primvar(*r);
  for (int l = 1; l <= depth; ++l) {
    DoublePoint* dst = levels[l].data();
    primvar.Interpolate(l, levels[l - 1].data(), dst);
  }
  FarLevel out;
  const size_t n = levels[depth].size();
  std::vector<DoublePoint> pos = levels[depth], du(n), dv(n);
  if (limit) {
    DoublePoint *p = pos.data(), *a = du.data(), *b = dv.data();
    primvar.Limit(levels[depth].data(), p, a, b);
  }
  std::vector<char> hole(m.face_sizes.size(), 0);
  for (int f : m.holes) hole[f] = 1;
  const std::vector<SurfaceCoord> coords = uniform_vertex_coords(*r, rule, depth);
  const Far::TopologyLevel& last = r->GetLevel(depth);
  for (size_t v = 0; v < n; ++v) {
    out.points.push_back({float(pos[v].p[0]), float(pos[v].p[1]), float(pos[v].p[2])});
    const float a[3] = {float(du[v].p[0]), float(du[v].p[1]), float(du[v].p[2])};
    const float b[3] = {float(dv[v].p[0]), float(dv[v].p[1]), float(dv[v].p[2])};
    out.normals.push_back(unit_cross(a, b));
    if (last.GetVertexFaces(static_cast<int>(v)).size() > 0)  // a vertex in no face has no coord
      out.at[grid_key(coords[v], depth)] = static_cast<int>(v);
    out.on_hole.push_back(coords[v].face < hole.size() && hole[coords[v].face]);
    out.faceless.push_back(last.GetVertexFaces(static_cast<int>(v)).size() == 0);
    out.special.push_back(!far_limit_is_exact(last, static_cast<int>(v), rule));
  }
  return out;
}

double distance(const Point3& a, const Point3& b) {
  return std::sqrt(double(a[0] - b[0]) * (a[0] - b[0]) + double(a[1] - b[1]) * (a[1] - b[1]) +
                   double(a[2] - b[2]) * (a[2] - b[2]));
}


Match compare(const Tessellation& t, const FarLevel& osd, int depth, double diagonal, bool normals) {
  Match m;
  std::vector<char> covered(osd.points.size(), 0);
  for (size_t i = 0; i < t.positions.size(); ++i) {
    auto it = osd.at.find(grid_key(t.coords[i], depth));
    if (it == osd.at.end()) {
      ++m.unmatched;
      continue;
    }
    covered[it->second] = 1;
    m.max_rel = std::max(m.max_rel, distance(t.positions[i], osd.points[it->second]) / diagonal);
    if (normals) {
      const Point3 &a = t.normals[i], &b = osd.normals[it->second];
      // atan2 of |a x b| and a . b: acos of a dot this close to 1 cannot resolve 0.01 degrees.
      const double c[3] = {double(a[1]) * b[2] - double(a[2]) * b[1], double(a[2]) * b[0] - double(a[0]) * b[2],
                           double(a[0]) * b[1] - double(a[1]) * b[0]};
      const double dot = double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2];
      m.max_deg = std::max(m.max_deg, std::atan2(std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), dot) * 180 / M_PI);
    }
  }
  for (size_t v = 0; v < covered.size(); ++v) m.uncovered += !covered[v] && !osd.on_hole[v] && osd.has_coord(v);
  return m;
}

}  // namespace sdb::conformance
