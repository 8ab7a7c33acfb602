#include "schemes/halfedge/surface.h"

#include <unistd.h>

#include <cstdio>
#include <numeric>

#include "harness/core/errors.h"
#include "harness/mesh/osd_topology.h"
#include "harness/refined/coords.h"

namespace sdb::halfedge {

void check_size(const ControlMesh& mesh, SubdivisionRule rule, int depth) {
  const Counts c = counts_at(mesh, rule, depth);
  char why[200];
  if (c.halfedges >= 4294967295.0 || c.vertices >= 4294967295.0) {
    std::snprintf(why, sizeof why, "depth %d makes %.3g halfedges and %.3g vertices, past 32-bit indices", depth,
                  c.halfedges, c.vertices);
    throw Unsupported(why);
  }
  // Every level's halfedges (twin, vertex, edge: 12 bytes, the levels before the last a third
  // more), points, the output (positions, normals, coords, triangles) and the limit plan.
  const double bytes = c.halfedges * 12 * 4.0 / 3 + c.vertices * (12 * 4.0 / 3 + 24 + 12 + 4) +
                       c.faces * (rule == SubdivisionRule::Loop ? 12 : 24);
  const double memory = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
  if (bytes > 0.6 * memory) {
    std::snprintf(why, sizeof why, "depth %d needs about %.1f GB, past 60%% of this machine's %.1f GB", depth,
                  bytes / 1e9, memory / 1e9);
    throw Unsupported(why);
  }
}

Surface::Surface(const ControlMesh& mesh, SubdivisionRule r, int d, bool p)
    : rule(r), depth(d), project(p), hierarchy(refine(mesh, r, d)), weights(smooth_weights(r)) {
  const Bounds b = bounds_of(mesh.positions);
  for (int k = 0; k < 3; ++k) origin[k] = static_cast<float>(b.centre(k));
  const Level& l = last();
  const uint32_t n = rule == SubdivisionRule::Loop ? 3 : 4;
  if (l.face_size != n) throw std::logic_error("halfedge: the last level's faces are not all of one size");
  // The first level of one face size (level 0, or level 1 of a Catmull-Clark mesh with other
  // faces): its vertices keep their numbers on every level after it.
  const int first = hierarchy.levels[0].face_size == n ? 0 : 1;
  if (project) {
    refined::EarlyLevel at_first;
    const refined::FaceLevel first_level = hierarchy.levels[first].face_level();
    if (first < d) {
      early = first;
      at_first.level = &first_level;
      at_first.last_of.resize(first_level.num_vertices);
      std::iota(at_first.last_of.begin(), at_first.last_of.end(), 0u);
    }
    limit = refined::plan_limit(l.face_level(), rule, sdc_options(mesh), early >= 0 ? &at_first : nullptr);
  }
  // Coords: the first level of one face size, then a corner split per level.
  refined::LevelCorners corners = refined::first_uniform_corners(mesh, rule);
  for (int k = first; k < d; ++k) corners = refined::split_corners(corners, n);
  out.coords = refined::vertex_coords(corners, l.vert.data(), l.num_vertices);
  out.triangles = refined::level_triangles(l.vert.data(), l.num_halfedges, n);
  out.positions.resize(l.num_vertices);
  out.normals.resize(l.num_vertices);
  // The frame reads nothing of the last level's halfedges (its points come from the level before,
  // the limit from the plan's rings): free them.
  Level& kept = hierarchy.levels.back();
  for (auto* v : {&kept.twin, &kept.vert, &kept.edge, &kept.edge_corner, &kept.vertex_corner}) std::vector<uint32_t>().swap(*v);
}

}  // namespace sdb::halfedge
