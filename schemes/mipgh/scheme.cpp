#include <cmath>
#include <cstdio>
#include <string>

#include "harness/core/errors.h"
#include "harness/core/registry.h"
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

SchemeInfo make_info(SubdivisionRule rule) {
  const bool loop = rule == SubdivisionRule::Loop;
  SchemeInfo info;
  info.name = loop ? "mipgh-loop" : "mipgh-cc";
  info.paper = "Shiue, Goel, Peters 2003, Mesh Mutation in Programmable Graphics Hardware";
  info.description = loop ? "D-atlas mesh processor with the Loop mesh shader, limit projection"
                          : "D-atlas mesh processor with the Catmull-Clark mesh shader, limit projection";
  info.role = SchemeRole::Method;
  info.reference = rule;
  info.level_kind = LevelKind::Depth;
  info.backends = {Backend::Cpu, Backend::CpuMt, Backend::Vulkan};
  info.default_levels = {1, 2, 3, 4};
  info.accepts.faces = loop ? MeshRequirements::Faces::TrianglesOnly : MeshRequirements::Faces::QuadsOnly;
  info.accepts.quadrangulate = !loop;  // R1: one Catmull-Clark step where a face is not a quad
  info.accepts.manifold = true;
  info.accepts.creases = true;
  info.accepts.holes = true;
  // Far's own limit masks at the last level (PrimvarRefiner::Limit): the bound the fragments
  // hold, where the reference's limit and Far's agree.
  info.bound = {1e-5, 0.01};
  info.peer = loop ? "osd-uniform-loop" : "osd-uniform";
  const std::string headline = loop ? "stanford/bunny" : "stein/sword_quad_dominant";
  info.default_meshes = loop ? std::vector<std::string>{"stanford/bunny", "crane/spot_low_resolution",
                                                        "pmp/icosahedron_subdiv"}
                             : std::vector<std::string>{"stein/sword_quad_dominant", "crane/spot_control",
                                                        "pmp/fandisk_quads"};
  info.headline_runs = {{headline, Backend::Cpu, 4}, {headline, Backend::CpuMt, 4}};
  // The paper's mutation steps alone (its cost claim, paper/cost.cpp): the last step's nodes are
  // the output, not the limit surface, so such a row lies off the limit by design.
  info.parameters = {{"limit", "1: project the last level to the limit surface; 0: output the last mutation step's nodes",
                      true, 1, 0, 1, 1}};
  return info;
}

class MipghScheme final : public Scheme {
 public:
  explicit MipghScheme(SubdivisionRule rule) : rule_(rule), info_(make_info(rule)) {}
  const SchemeInfo& info() const override { return info_; }

  std::optional<std::string> unsupported(const RunRequest& r) const override {
    if (r.level < 0 || r.level > kMaxDepth) return "depth must be 0.." + std::to_string(kMaxDepth);
    if (r.backend == Backend::Vulkan)
      if (auto why = vulkan_unavailable()) return *why;
    return std::nullopt;
  }

  std::unique_ptr<Evaluation> prepare(const ControlMesh& mesh, const RunRequest& r) const override {
    return make_evaluation(mesh, rule_, r, r.parameters.integer("limit") == 1);
  }

 private:
  SubdivisionRule rule_;
  SchemeInfo info_;
};

}  // namespace

std::vector<PaperTable> mipgh_paper_tables();  // paper/cost.cpp

namespace {

std::vector<std::unique_ptr<Scheme>> make_mipgh_schemes() {
  std::vector<std::unique_ptr<Scheme>> s;
  s.push_back(std::make_unique<MipghScheme>(SubdivisionRule::CatmullClark));
  s.push_back(std::make_unique<MipghScheme>(SubdivisionRule::Loop));
  return s;
}

SDB_REGISTER_SCHEMES(mipgh, make_mipgh_schemes);
SDB_REGISTER_PAPER_TABLES(mipgh, mipgh_paper_tables);

}  // namespace

std::unique_ptr<Evaluation> make_evaluation(const ControlMesh& mesh, SubdivisionRule rule, const RunRequest& r,
                                            bool project_to_limit) {
  DAtlas atlas = build_atlas(mesh, rule == SubdivisionRule::Loop ? FacetKinds::Triangles : FacetKinds::Quads);
  const double nodes = node_count(atlas, r.level);
  const double bytes = nodes * (2 * sizeof(V3) + 2 * sizeof(Point3)) +
                       atlas.num_facets() * std::ldexp(1.0, 2 * r.level) * 4 * 4.0 / 3 * 2;
  if (bytes > kMaxBytes || nodes >= 4294967295.0) {
    char why[160];
    std::snprintf(why, sizeof why, "depth %d would take %.1f GB of nodes and indices, past the %.0f GB limit",
                  r.level, bytes / 1e9, kMaxBytes / 1e9);
    throw Unsupported(why);
  }
  if (r.backend == Backend::Vulkan) return make_vulkan_evaluation(mesh, rule, std::move(atlas), r.level, project_to_limit);
  return std::make_unique<CpuMipghEvaluation>(mesh, rule, std::move(atlas), r.level, r.backend == Backend::CpuMt,
                                              r.threads, project_to_limit);
}

}  // namespace sdb::mipgh
