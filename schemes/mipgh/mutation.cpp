#include "schemes/mipgh/mutation.h"

#include <string>
#include <utility>

#include "harness/core/errors.h"
#include "harness/mesh/osd_topology.h"
#include "schemes/mipgh/primitives.h"

namespace sdb::mipgh {

MeshMutation::Topology MeshMutation::topology_of(const ControlMesh& mesh, MeshRule rule, DAtlas atlas, int inner) {
  const auto refiner = make_refiner(mesh, far_rule(rule));
  const auto& base = refiner->GetLevel(0);
  // Far makes holes of the faces it is told of, and under the boundary rule "none" of every face
  // at a boundary vertex: primitive compilation skips the same ones.
  for (int f = 0; f < atlas.num_facets(); ++f) atlas.facet_hole[f] |= base.IsFaceHole(f);
  EdgeTags tags = build_tags(atlas, base, sdc_options(mesh), inner);
  return {std::move(atlas), std::move(tags)};
}

MeshMutation::MeshMutation(const ControlMesh& mesh, MeshRule rule, DAtlas atlas, int depth, bool project,
                           AdaptiveCriterion criterion)
    : MeshMutation(mesh, rule, topology_of(mesh, rule, std::move(atlas), project ? limit_depth_for(mesh, depth) : depth),
                   depth, project ? limit_depth_for(mesh, depth) : depth, project, criterion) {}

std::vector<uint8_t> MeshMutation::home_levels(const ControlMesh& mesh, int depth, bool project) {
  std::vector<uint8_t> home(depth + 1);
  for (int l = 0; l <= depth; ++l) home[l] = uint8_t(project ? limit_depth_for(mesh, l) : l);
  return home;
}

DLoD MeshMutation::lay_out(const DAtlas& atlas, const std::vector<uint8_t>& render, const std::vector<uint8_t>& home,
                           int inner) {
  if (render.empty()) return DLoD(atlas, inner);
  std::vector<uint8_t> labels(render);
  for (uint8_t& l : labels) l = home[l];
  return DLoD(atlas, inner, std::move(labels));
}

MeshMutation::MeshMutation(const ControlMesh& mesh, MeshRule rule, Topology topology, int depth, int inner,
                           bool project, AdaptiveCriterion criterion)
    : atlas(std::move(topology.atlas)),
      render(criterion.kind == Refinement::Uniform ? std::vector<uint8_t>{}
                                                   : facet_labels(atlas, mesh.positions, criterion, depth)),
      home(home_levels(mesh, depth, project)),
      lod(lay_out(atlas, render, home, inner)),
      tags(std::move(topology.tags)),
      shader(make_shader(rule, sdc_options(mesh))),
      processor(atlas, lod, tags, *shader),
      pick(inner > depth && render.empty() ? same_points_at(atlas, lod, depth, inner) : std::vector<uint32_t>{}),
      base_tangents(project && rule != MeshRule::QuadTri
                        ? compose_base_tangents(processor, *shader,
                                                render.empty() ? std::vector<uint8_t>(atlas.num_vertices, uint8_t(inner))
                                                               : vertex_homes(atlas, render, home))
                        : BaseTangents{}),
      patches(project && rule == MeshRule::CatmullClark ? find_regular_patches(atlas, tags, inner) : RegularPatches{}),
      facet_masks(project && rule == MeshRule::CatmullClark ? compose_facet_masks(mesh, atlas, tags, patches, inner)
                                                            : FacetMasks{}),
      depth_(depth),
      project_(project) {
  for (int v = 0; v < atlas.num_vertices; ++v)
    if (atlas.vertex_fans[v] > 1 && !(tags.any && tags.vertex[0][v] >= 10.0f))
      throw InputError(mesh.source, "vertex " + std::to_string(v) +
                                        " joins several fans of faces and is not an infinitely sharp corner");
  const Bounds box = bounds_of(mesh.positions);
  for (int k = 0; k < 3; ++k) origin[k] = static_cast<float>(box.centre(k));
}

}  // namespace sdb::mipgh
