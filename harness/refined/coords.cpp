#include "harness/refined/coords.h"

#include <stdexcept>

namespace sdb::refined {
namespace {

CornerCoord sum(const CornerCoord& a, const CornerCoord& b) { return {a.face, a.u + b.u, a.v + b.v}; }
CornerCoord twice(const CornerCoord& a) { return {a.face, 2 * a.u, 2 * a.v}; }

}  // namespace

LevelCorners first_uniform_corners(const ControlMesh& mesh, SubdivisionRule rule) {
  bool all_quads = true;
  for (int n : mesh.face_sizes) all_quads = all_quads && n == 4;
  LevelCorners out;
  uint32_t ptex = 0;
  if (rule == SubdivisionRule::Loop || all_quads) {
    for (int n : mesh.face_sizes) {
      if (n == 3 && rule == SubdivisionRule::Loop) out.corners.insert(out.corners.end(), {{ptex, 0, 0}, {ptex, 1, 0}, {ptex, 0, 1}});
      else if (n == 4 && rule == SubdivisionRule::CatmullClark)
        out.corners.insert(out.corners.end(), {{ptex, 0, 0}, {ptex, 1, 0}, {ptex, 1, 1}, {ptex, 0, 1}});
      else throw std::invalid_argument("first_uniform_corners: a face of the wrong size for the rule");
      ++ptex;
    }
    return out;
  }
  // Catmull-Clark with other faces: level 1, in units of 1/2. A quad's corner child is a quadrant
  // of its ptex face; corner k of another face has the ptex sub-face ptex + k to itself.
  out.scale = 1;
  for (int n : mesh.face_sizes) {
    for (int k = 0; k < n; ++k) {
      if (n == 4) {
        static const uint32_t quad[4][2] = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
        auto at = [&](int j) { return CornerCoord{ptex, quad[(j + 4) % 4][0], quad[(j + 4) % 4][1]}; };
        auto mid = [&](int a, int b) { return CornerCoord{ptex, (at(a).u + at(b).u) / 2, (at(a).v + at(b).v) / 2}; };
        out.corners.insert(out.corners.end(), {at(k), mid(k, k + 1), {ptex, 1, 1}, mid(k - 1, k)});
      } else {
        const uint32_t sub = ptex + k;
        out.corners.insert(out.corners.end(), {{sub, 0, 0}, {sub, 2, 0}, {sub, 2, 2}, {sub, 0, 2}});
      }
    }
    ptex += n == 4 ? 1 : n;
  }
  return out;
}

LevelCorners split_corners(const LevelCorners& parent, uint32_t n) {
  LevelCorners out;
  out.scale = parent.scale + 1;
  const size_t faces = parent.corners.size() / n;
  out.corners.resize(parent.corners.size() * 4);
  for (size_t f = 0; f < faces; ++f) {
    const CornerCoord* c = &parent.corners[n * f];
    for (uint32_t i = 0; i < n; ++i) {
      const CornerCoord &here = c[i], &next = c[(i + 1) % n], &prev = c[(i + n - 1) % n];
      CornerCoord* child = &out.corners[n * (n * f + i)];
      child[0] = twice(here);
      child[1] = sum(here, next);
      if (n == 4) {
        child[2] = {here.face, (c[0].u + c[1].u + c[2].u + c[3].u) / 2, (c[0].v + c[1].v + c[2].v + c[3].v) / 2};
        child[3] = sum(prev, here);
      } else {
        child[2] = sum(prev, here);
        out.corners[n * (n * faces + f) + i] = sum(prev, here);  // the middle triangle's corner i
      }
    }
  }
  return out;
}

std::vector<SurfaceCoord> vertex_coords(const LevelCorners& level, const uint32_t* verts, uint32_t num_vertices) {
  std::vector<SurfaceCoord> coords(num_vertices);
  std::vector<char> seen(num_vertices, 0);
  const float unit = 1.0f / static_cast<float>(1u << level.scale);
  for (size_t c = 0; c < level.corners.size(); ++c) {
    const uint32_t v = verts[c];
    if (seen[v]) continue;
    seen[v] = 1;
    const CornerCoord& k = level.corners[c];
    coords[v] = {k.face, static_cast<float>(k.u) * unit, static_cast<float>(k.v) * unit};
  }
  return coords;
}

std::vector<uint32_t> level_triangles(const uint32_t* verts, uint64_t corners, uint32_t n) {
  std::vector<uint32_t> t;
  t.reserve(n == 4 ? corners / 4 * 6 : corners);
  for (uint64_t c = 0; c < corners; c += n) {
    if (n == 4) t.insert(t.end(), {verts[c], verts[c + 1], verts[c + 2], verts[c], verts[c + 2], verts[c + 3]});
    else t.insert(t.end(), {verts[c], verts[c + 1], verts[c + 2]});
  }
  return t;
}

}  // namespace sdb::refined
