#include "schemes/edgefriend/surface.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "harness/core/errors.h"
#include "harness/mesh/osd_topology.h"
#include "harness/refined/coords.h"

namespace sdb::edgefriend {
namespace {

namespace Far = OpenSubdiv::Far;

std::unique_ptr<Far::TopologyRefiner> level1_of(const ControlMesh& mesh) {
  auto r = make_refiner(mesh, SubdivisionRule::CatmullClark);
  Far::TopologyRefiner::UniformOptions o(1);
  o.fullTopologyInLastLevel = true;
  r->RefineUniform(o);
  return r;
}

}  // namespace

void check_size(const ControlMesh& mesh, int depth) {
  const Counts c = counts_at(mesh, depth);
  char why[200];
  if (4 * c.quads >= 4294967295.0 || c.vertices >= 4294967295.0) {
    std::snprintf(why, sizeof why, "depth %d makes %.3g quads and %.3g vertices, past 32-bit indices", depth, c.quads, c.vertices);
    throw Unsupported(why);
  }
  // Every level's quads (indices and friends: 32 bytes, the levels before the last a third more)
  // and points, the output (positions, normals, coords, triangles, its faces) and the limit plan.
  const double bytes = c.quads * (32 * 4.0 / 3 + 24 + 8) + c.vertices * (12 * 4.0 / 3 + 4 * 4.0 / 3 + 24 + 12 + 36);
  const double memory = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
  if (bytes > 0.6 * memory) {
    std::snprintf(why, sizeof why, "depth %d needs about %.1f GB, past 60%% of this machine's %.1f GB", depth, bytes / 1e9,
                  memory / 1e9);
    throw Unsupported(why);
  }
}

Surface::Surface(const ControlMesh& mesh, int d, bool p) : depth(d), project(p), weights(smooth_weights()) {
  {
    const auto level1 = level1_of(mesh);
    hierarchy = refine(mesh, *level1, d);
    stencils = first_step(*level1, hierarchy);
  }
  const Bounds b = bounds_of(mesh.positions);
  for (int k = 0; k < 3; ++k) origin[k] = static_cast<float>(b.centre(k));
  if (project) {
    // Special vertices that level 1 has take their limit from their ring there (limit.h, EarlyLevel).
    refined::EarlyLevel at_first;
    const FirstLevelFaces first = d > 1 ? first_level_faces(hierarchy) : FirstLevelFaces{};
    const refined::FaceLevel first_level = first.face_level();
    if (d > 1) early = 0, at_first.level = &first_level, at_first.last_of = first.last_of;
    limit = refined::plan_limit(hierarchy.face_level(), SubdivisionRule::CatmullClark, sdc_options(mesh),
                                early >= 0 ? &at_first : nullptr);
  }
  // Coords: level 1 (a quad mesh's level 0 split once), then a corner split per level.
  refined::LevelCorners corners = refined::first_uniform_corners(mesh, SubdivisionRule::CatmullClark);
  if (std::all_of(mesh.face_sizes.begin(), mesh.face_sizes.end(), [](int n) { return n == 4; }))
    corners = refined::split_corners(corners, 4);
  for (int k = 1; k < d; ++k) corners = refined::split_corners(corners, 4);
  if (corners.corners.size() != hierarchy.out_verts.size()) throw std::logic_error("edgefriend: coords and quads differ");
  out.coords = refined::vertex_coords(corners, hierarchy.out_verts.data(), hierarchy.out_vertices);
  out.triangles = refined::level_triangles(hierarchy.out_verts.data(), hierarchy.out_verts.size(), 4);
  out.positions.resize(hierarchy.out_vertices);
  out.normals.resize(hierarchy.out_vertices);
  // The frame reads nothing of the last level's quads (its points come from the level before,
  // the limit from the plan's rings).
  Level& kept = hierarchy.levels.back();
  std::vector<uint32_t>().swap(kept.indices);
  std::vector<Friends>().swap(kept.friends);
  std::vector<uint32_t>().swap(kept.vertex_corner);
  for (auto* v : {&hierarchy.out_verts, &hierarchy.out_twin}) std::vector<uint32_t>().swap(*v);
  std::vector<float>().swap(hierarchy.out_edge_sharpness);
}

}  // namespace sdb::edgefriend
