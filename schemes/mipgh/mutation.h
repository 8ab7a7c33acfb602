// What every backend builds in prepare from a mesh: the D-atlas with Far's holes, the D-LoD and
// edge tags to the depth the limit needs, the mesh shader and the processor over them. Fixed
// after initialization (Section 3.2); the backends differ only in how they run the steps.
#pragma once

#include <memory>
#include <vector>

#include "harness/core/control_mesh.h"
#include "schemes/mipgh/adaptive.h"
#include "schemes/mipgh/atlas.h"
#include "schemes/mipgh/lod.h"
#include "schemes/mipgh/mipgh.h"
#include "schemes/mipgh/processor.h"
#include "schemes/mipgh/facet_masks.h"
#include "schemes/mipgh/regular_patches.h"
#include "schemes/mipgh/shader.h"

namespace sdb::mipgh {

class MeshMutation {
 public:
  // `atlas`: the mesh's (build_atlas), as the size check in prepare built it. Throws InputError
  // for a vertex of several fans that Far does not make an infinitely sharp corner.
  // A criterion other than Uniform labels the D-facets (adaptive.h): `render` holds the labels,
  // the DLoD refines each D-facet to its label (plus the levels `pick` would add).
  MeshMutation(const ControlMesh& mesh, MeshRule rule, DAtlas atlas, int depth, bool project_to_limit,
               AdaptiveCriterion criterion = {});
  MeshMutation(const MeshMutation&) = delete;
  MeshMutation& operator=(const MeshMutation&) = delete;

  int depth() const { return depth_; }              // the output's level
  int inner_depth() const { return lod.depth(); }   // the last level refined (deeper for the limit)
  bool project() const { return project_; }

  const DAtlas atlas;
  const std::vector<uint8_t> render;  // adaptive: each D-facet's drawn level; empty: uniform
  // Adaptive: the level a drawn level's nodes come from (deeper where semi-sharp creases outlast
  // it, as `pick` does for the depth: limit_depth_for of each level).
  const std::vector<uint8_t> home;
  const DLoD lod;
  const EdgeTags tags;
  const std::unique_ptr<MeshShader> shader;
  const MeshProcessor processor;
  // Where semi-sharp creases outlast the depth, refined to limit_depth_for and sampled at the
  // depth's grid points: output node i is inner node pick[i] (empty: the same level, or adaptive).
  const std::vector<uint32_t> pick;
  // Projection: the D-vertices' limit tangents at their level as weights on level 0 (vertex_tangents.h).
  const BaseTangents base_tangents;
  // Projection, Catmull-Clark: the regular D-facets' normals from their bicubic patches on level 0.
  const RegularPatches patches;
  // And the other untagged interior D-facets' normals from their 1-ring on level 0.
  const FacetMasks facet_masks;
  float origin[3];  // levels are refined relative to the control box's centre: float keeps its precision

 private:
  struct Topology {
    DAtlas atlas;
    EdgeTags tags;
  };
  static Topology topology_of(const ControlMesh& mesh, MeshRule rule, DAtlas atlas, int inner);
  MeshMutation(const ControlMesh& mesh, MeshRule rule, Topology topology, int depth, int inner, bool project,
               AdaptiveCriterion criterion);
  static DLoD lay_out(const DAtlas& atlas, const std::vector<uint8_t>& render, const std::vector<uint8_t>& home,
                      int inner);
  static std::vector<uint8_t> home_levels(const ControlMesh& mesh, int depth, bool project);

  int depth_;
  bool project_;
};

}  // namespace sdb::mipgh
