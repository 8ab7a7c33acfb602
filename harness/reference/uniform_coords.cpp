// Tracks each refined face's corners through the levels in ptex space: a child face's vertices
// are children of its parent's corners (same coord), edges (midpoint of the edge's corner coords)
// or the face itself (centre). This needs no assumption about how Far orders or rotates child
// faces. The one special case is the first Catmull-Clark level of an n-gon, whose children are
// the ptex sub-faces: corner (0,0), next edge (1,0), centre (1,1), previous edge (0,1).
#include "harness/reference/uniform_coords.h"

#include <opensubdiv/far/ptexIndices.h>

#include <array>

namespace sdb {
namespace {

namespace Far = OpenSubdiv::Far;

struct UV {
  uint32_t face;
  float u, v;
};

UV mid(const UV& a, const UV& b) { return {a.face, 0.5f * (a.u + b.u), 0.5f * (a.v + b.v)}; }

// Corner coords of every face of one level, concatenated in face-vertex order.
using FaceCorners = std::vector<UV>;

FaceCorners base_corners(const Far::TopologyRefiner& r, SubdivisionRule rule) {
  const Far::TopologyLevel& l0 = r.GetLevel(0);
  const Far::PtexIndices ptex(r);
  FaceCorners out;
  for (int f = 0; f < l0.GetNumFaces(); ++f) {
    const uint32_t id = ptex.GetFaceId(f);
    const int n = l0.GetFaceVertices(f).size();
    if (rule == SubdivisionRule::Loop) out.insert(out.end(), {{id, 0, 0}, {id, 1, 0}, {id, 0, 1}});
    else if (n == 4) out.insert(out.end(), {{id, 0, 0}, {id, 1, 0}, {id, 1, 1}, {id, 0, 1}});
    else
      for (int k = 0; k < n; ++k) out.push_back({id + k, 0, 0});  // n-gon corner k: origin of sub-face k
  }
  return out;
}

// Loop splits triangles without a face vertex; Far has no face-child table then.
FaceCorners refine_corners(const Far::TopologyRefiner& r, int level, const FaceCorners& parent, bool ngon_split,
                           bool has_face_vertex) {
  const Far::TopologyLevel& pl = r.GetLevel(level - 1);
  const Far::TopologyLevel& cl = r.GetLevel(level);
  const Far::PtexIndices ptex(r);
  std::vector<int> parent_off(pl.GetNumFaces() + 1, 0), child_off(cl.GetNumFaces() + 1, 0);
  for (int f = 0; f < pl.GetNumFaces(); ++f) parent_off[f + 1] = parent_off[f] + pl.GetFaceVertices(f).size();
  for (int f = 0; f < cl.GetNumFaces(); ++f) child_off[f + 1] = child_off[f] + cl.GetFaceVertices(f).size();
  FaceCorners out(child_off.back());
  for (int f = 0; f < pl.GetNumFaces(); ++f) {
    Far::ConstIndexArray fv = pl.GetFaceVertices(f), fe = pl.GetFaceEdges(f), children = pl.GetFaceChildFaces(f);
    const int n = fv.size();
    const UV* pc = &parent[parent_off[f]];
    const bool subfaces = ngon_split && n != 4;
    UV centre = {pc[0].face, 0, 0};
    for (int k = 0; k < n; ++k) centre.u += pc[k].u / n, centre.v += pc[k].v / n;
    const int face_vertex = has_face_vertex ? pl.GetFaceChildVertex(f) : -1;
    for (int c : children) {
      Far::ConstIndexArray cv = cl.GetFaceVertices(c);
      int corner = -1;  // the parent corner this child face touches (n-gon sub-faces)
      for (int j = 0; j < cv.size(); ++j)
        for (int k = 0; k < n; ++k)
          if (pl.GetVertexChildVertex(fv[k]) == cv[j]) corner = k;
      for (int j = 0; j < cv.size(); ++j) {
        UV& dst = out[child_off[c] + j];
        const int v = cv[j];
        if (subfaces) {
          const uint32_t id = ptex.GetFaceId(f) + corner;
          if (v == face_vertex) dst = {id, 1, 1};
          else if (v == pl.GetEdgeChildVertex(fe[corner])) dst = {id, 1, 0};
          else if (v == pl.GetEdgeChildVertex(fe[(corner + n - 1) % n])) dst = {id, 0, 1};
          else dst = {id, 0, 0};
          continue;
        }
        if (v == face_vertex) {
          dst = centre;
          continue;
        }
        bool found = false;
        for (int k = 0; k < n && !found; ++k) {
          if (v == pl.GetVertexChildVertex(fv[k])) dst = pc[k], found = true;
          else if (v == pl.GetEdgeChildVertex(fe[k])) dst = mid(pc[k], pc[(k + 1) % n]), found = true;
        }
      }
    }
  }
  return out;
}

FaceCorners corners_at(const Far::TopologyRefiner& r, SubdivisionRule rule, int level) {
  FaceCorners corners = base_corners(r, rule);
  const bool catmark = rule == SubdivisionRule::CatmullClark;
  for (int l = 1; l <= level; ++l) corners = refine_corners(r, l, corners, l == 1 && catmark, catmark);
  return corners;
}

}  // namespace

std::vector<uint32_t> uniform_triangles(const Far::TopologyRefiner& r, int level) {
  const Far::TopologyLevel& l = r.GetLevel(level);
  std::vector<uint32_t> triangles;
  for (int f = 0; f < l.GetNumFaces(); ++f) {
    if (l.IsFaceHole(f)) continue;
    Far::ConstIndexArray fv = l.GetFaceVertices(f);
    for (int k = 1; k + 1 < fv.size(); ++k)
      triangles.insert(triangles.end(), {uint32_t(fv[0]), uint32_t(fv[k]), uint32_t(fv[k + 1])});
  }
  return triangles;
}

std::vector<SurfaceCoord> uniform_face_corner_coords(const Far::TopologyRefiner& r, SubdivisionRule rule, int level) {
  std::vector<SurfaceCoord> out;
  for (const UV& c : corners_at(r, rule, level)) out.push_back({c.face, c.u, c.v});
  return out;
}

std::vector<SurfaceCoord> uniform_vertex_coords(const Far::TopologyRefiner& r, SubdivisionRule rule, int level) {
  const FaceCorners corners = corners_at(r, rule, level);
  const Far::TopologyLevel& lv = r.GetLevel(level);
  std::vector<SurfaceCoord> coords(lv.GetNumVertices());
  std::vector<char> seen(lv.GetNumVertices(), 0);
  // Coords from faces with a surface first: a vertex shared with a hole takes its other face's.
  for (int pass = 0; pass < 2; ++pass)
    for (int f = 0, i = 0; f < lv.GetNumFaces(); ++f) {
      Far::ConstIndexArray fv = lv.GetFaceVertices(f);
      if (lv.IsFaceHole(f) != (pass == 1)) {
        i += fv.size();
        continue;
      }
      for (int j = 0; j < fv.size(); ++j, ++i)
        if (!seen[fv[j]]) {
          seen[fv[j]] = 1;
          coords[fv[j]] = {corners[i].face, corners[i].u, corners[i].v};
        }
    }
  return coords;
}

}  // namespace sdb
