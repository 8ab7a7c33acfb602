#include <cmath>
#include <cstdio>
#include <string>

#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/mesh/osd_topology.h"
#include "schemes/mipgh/atlas.h"
#include "schemes/mipgh/cpu.h"
#include "schemes/mipgh/lod.h"
#include "schemes/mipgh/mipgh.h"
#include "schemes/mipgh/vulkan.h"

namespace sdb::mipgh {
namespace {

constexpr int kMaxDepth = 8;
// Two level buffers, the output's positions and normals, the D-LoD's indices: past this a
// request is refused before anything is built.
constexpr double kMaxBytes = 8e9;

const char* scheme_name(MeshRule rule) {
  switch (rule) {
    case MeshRule::Loop: return "mipgh-loop";
    case MeshRule::QuadTri: return "mipgh-quadtri";
    default: return "mipgh-cc";
  }
}

SchemeInfo make_info(MeshRule rule) {
  const bool loop = rule == MeshRule::Loop, quadtri = rule == MeshRule::QuadTri;
  SchemeInfo info;
  info.name = scheme_name(rule);
  info.paper = "Shiue, Goel, Peters 2003, Mesh Mutation in Programmable Graphics Hardware";
  info.description = loop      ? "D-atlas mesh processor with the Loop mesh shader, limit projection"
                     : quadtri ? "D-atlas mesh processor with Stam and Loop's quad/triangle mesh shader, last level's nodes"
                               : "D-atlas mesh processor with the Catmull-Clark mesh shader, limit projection";
  info.role = SchemeRole::Method;
  info.reference = far_rule(rule);
  info.level_kind = LevelKind::Depth;
  // Measured 171 (fragments-cc) and 181 (mipgh-cc) bytes per output triangle at a validated run's
  // peak (harness/bench/notes/limits-2026-12-07.md); 256 leaves two fifths to spare.
  info.peak_bytes_per_triangle = 256;
  info.backends = {Backend::Cpu, Backend::CpuMt, Backend::Vulkan};
  info.default_levels = {1, 2, 3, 4};
  info.accepts.faces = loop ? MeshRequirements::Faces::TrianglesOnly
                       : quadtri ? MeshRequirements::Faces::Any
                                 : MeshRequirements::Faces::QuadsOnly;
  info.accepts.quadrangulate = rule == MeshRule::CatmullClark;  // R1: one Catmull-Clark step where a face is not a quad
  info.accepts.split_polygons = quadtri;  // R1 for quads and triangles: larger faces split into them
  info.accepts.manifold = true;
  info.accepts.creases = true;
  info.accepts.holes = true;
  // Far's own limit masks at the last level (PrimvarRefiner::Limit): the bound the fragments
  // hold, where the reference's limit and Far's agree. The quad/triangle surface is another one,
  // and its last level's nodes are not on it: its distance from Catmull-Clark's limit is reported,
  // not bounded.
  info.bound = quadtri ? DeviationBound{} : DeviationBound{1e-5, 0.01};
  info.surface_coords = !quadtri;  // its rows carry the Hausdorff distance (cpu.cpp)
  // mipgh-quadtri is held to the Catmull-Clark limit of the mesh as given (its rule on quads; no
  // evaluator exists for Stam and Loop's surface), by nearest points: it approximates. The others
  // reproduce their limit unless `limit=0` leaves the last step's nodes unprojected.
  info.limit = quadtri ? LimitClaim::Approximates : LimitClaim::Reproduces;
  info.limit_projection_parameter = quadtri ? "" : "limit";
  info.peer = loop ? "osd-uniform-loop" : "osd-uniform";
  const std::string headline = loop ? "stanford/bunny" : "stein/sword_quad_dominant";
  info.default_meshes = loop      ? std::vector<std::string>{"stanford/bunny", "crane/spot_low_resolution",
                                                             "pmp/icosahedron_subdiv"}
                        : quadtri ? std::vector<std::string>{"stein/sword_quad_dominant", "pmp/suzanne",
                                                             "crane/spot_control", "crane/blub_control"}
                                  : std::vector<std::string>{"stein/sword_quad_dominant", "crane/spot_control",
                                                             "pmp/fandisk_quads"};
  info.headline_runs = {{headline, Backend::Cpu, 4}, {headline, Backend::CpuMt, 4}};
  // Adaptive refinement (Figures 13, 14; adaptive.h): the criterion that labels the D-facets.
  const std::vector<ParameterSpec> adaptive = {
      {"adapt", "0: uniform; adaptive by 1: region (x below extent of the box), 2: curvature, 3: camera distance",
       true, 0, 0, 3, 1},
      {"extent", "adaptive: the region's fraction of the box, the fraction of the largest bend refined fully, or "
                 "the doublings of camera distance per level",
       false, 0.5, 0.05, 1, 0}};
  if (quadtri) {
    // No limit masks are known where quads and triangles meet: the last level's nodes, normals zero.
    info.parameters = {{"limit", "0 only: no limit masks are known where quads and triangles meet", true, 0, 0, 0, 1}};
    info.parameters.insert(info.parameters.end(), adaptive.begin(), adaptive.end());
    return info;
  }
  // The paper's mutation steps alone (its cost claim, paper/cost.cpp): the last step's nodes are
  // the output, not the limit surface, so such a row lies off the limit by design.
  info.parameters = {{"limit", "1: project the last level to the limit surface; 0: output the last mutation step's nodes",
                      true, 1, 0, 1, 1}};
  info.parameters.insert(info.parameters.end(), adaptive.begin(), adaptive.end());
  return info;
}

class MipghScheme final : public Scheme {
 public:
  explicit MipghScheme(MeshRule rule) : rule_(rule), info_(make_info(rule)) {}
  const SchemeInfo& info() const override { return info_; }

  std::optional<std::string> unsupported(const RunRequest& r) const override {
    if (r.level < 0 || r.level > kMaxDepth) return "depth must be 0.." + std::to_string(kMaxDepth);
    if (r.backend == Backend::Vulkan)
      if (auto why = vulkan_unavailable()) return *why;
    return std::nullopt;
  }

  std::unique_ptr<Evaluation> prepare(const ControlMesh& mesh, const RunRequest& r) const override {
    const AdaptiveCriterion criterion{Refinement(r.parameters.integer("adapt")), r.parameters.value("extent")};
    return make_evaluation(mesh, rule_, r, r.parameters.integer("limit") == 1, criterion);
  }

 private:
  MeshRule rule_;
  SchemeInfo info_;
};

std::vector<std::unique_ptr<Scheme>> make_mipgh_schemes() {
  std::vector<std::unique_ptr<Scheme>> s;
  s.push_back(std::make_unique<MipghScheme>(MeshRule::CatmullClark));
  s.push_back(std::make_unique<MipghScheme>(MeshRule::Loop));
  s.push_back(std::make_unique<MipghScheme>(MeshRule::QuadTri));
  return s;
}

SDB_REGISTER_SCHEMES(mipgh, make_mipgh_schemes);

}  // namespace

std::unique_ptr<Evaluation> make_evaluation(const ControlMesh& mesh, MeshRule rule, const RunRequest& r,
                                            bool project_to_limit, AdaptiveCriterion criterion) {
  if (rule == MeshRule::QuadTri && project_to_limit)
    throw Unsupported("mipgh-quadtri has no limit masks where quads and triangles meet");
  const FacetKinds kinds = rule == MeshRule::Loop      ? FacetKinds::Triangles
                           : rule == MeshRule::QuadTri ? FacetKinds::QuadsAndTriangles
                                                       : FacetKinds::Quads;
  DAtlas atlas = build_atlas(mesh, kinds);
  const double nodes = node_count(atlas, r.level);
  const double bytes = nodes * (2 * sizeof(V3) + 2 * sizeof(Point3)) +
                       atlas.num_facets() * std::ldexp(1.0, 2 * r.level) * 4 * 4.0 / 3 * 2;
  if (bytes > kMaxBytes || nodes >= 4294967295.0) {
    char why[160];
    std::snprintf(why, sizeof why, "depth %d would take %.1f GB of nodes and indices, past the %.0f GB limit",
                  r.level, bytes / 1e9, kMaxBytes / 1e9);
    throw Unsupported(why);
  }
  // Every level down to the inner depth is refined whole: 2^22 faces there at most.
  if (project_to_limit)
    if (auto why = limit_depth_refusal(mesh, r.level, atlas.num_facets(), double(1 << 22))) throw Unsupported(*why);
  if (r.backend == Backend::Vulkan)
    return make_vulkan_evaluation(mesh, rule, std::move(atlas), r.level, project_to_limit, criterion);
  return std::make_unique<CpuMipghEvaluation>(mesh, rule, std::move(atlas), r.level, r.backend == Backend::CpuMt,
                                              r.threads, project_to_limit, criterion);
}

}  // namespace sdb::mipgh
