#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/refined/requests.h"
#include "schemes/halfedge/halfedge.h"
#include "schemes/halfedge/surface.h"
#include "schemes/halfedge/vulkan.h"

namespace sdb::halfedge {
namespace {

SchemeInfo make_info(SubdivisionRule rule) {
  const bool loop = rule == SubdivisionRule::Loop;
  SchemeInfo info;
  info.name = loop ? "halfedge-loop" : "halfedge-cc";
  info.paper = loop ? "Vanhoey, Dupuy 2022, A Halfedge Refinement Rule for Parallel Loop Subdivision (EG short paper)"
                    : "Dupuy, Vanhoey 2021, A Halfedge Refinement Rule for Parallel Catmull-Clark Subdivision (HPG)";
  info.description = loop ? "peer: Loop halfedge refinement to depth k (gather), limit projection with Far's masks"
                          : "peer: Catmull-Clark halfedge refinement to depth k (gather), limit projection with Far's masks";
  info.role = SchemeRole::Peer;
  info.reference = rule;
  info.level_kind = LevelKind::Depth;
  // Measured 198 (halfedge-cc, the sword, validate at depths 2 and 3) and 134 (halfedge-loop, the
  // bunny) bytes per output triangle at a validated run's peak; a bench's peak at depth 4 is 111
  // to 134 on cpu, cpu-mt and vulkan (notes/2026-12-07-limit.md). On lavapipe the device's buffers
  // are the process's memory too: validate --backend vulkan on the sword at depth 5 (45.8 M
  // triangles) peaked at 12,486,248 KiB, 279 bytes a triangle with the baseline
  // (notes/2026-12-08-issues-size.md). 336 leaves a fifth over that.
  info.peak_bytes_per_triangle = 336;
  info.backends = {Backend::Cpu, Backend::CpuMt, Backend::Vulkan};
  info.default_levels = {1, 2, 3, 4};
  info.accepts.faces = loop ? MeshRequirements::Faces::TrianglesOnly : MeshRequirements::Faces::Any;
  info.accepts.manifold = true;  // a halfedge has one twin
  info.accepts.creases = true;
  info.accepts.holes = false;
  // Judged as osd-uniform(-loop), whose refinement and limit masks these equal: Catmull-Clark
  // without a bound (Far's masks take a semi-sharp crease left at the depth as infinite; the
  // figures are reported), Loop within osd-uniform-loop's.
  if (loop) info.bound = {1e-5, 0.05};
  // Read against OpenSubdiv's uniform refinement at the same depth (its cpu row on every backend).
  info.peer = loop ? "osd-uniform-loop" : "osd-uniform";
  info.default_meshes = loop ? std::vector<std::string>{"stanford/bunny", "crane/spot_low_resolution",
                                                        "pmp/icosahedron_subdiv"}
                             : std::vector<std::string>{"stein/sword_quad_dominant", "crane/spot_control",
                                                        "pmp/fandisk_quads"};
  info.headline_runs = {{loop ? "stanford/bunny" : "stein/sword_quad_dominant", Backend::CpuMt, 4}};
  return info;
}

class HalfedgeScheme final : public Scheme {
 public:
  explicit HalfedgeScheme(SubdivisionRule rule) : rule_(rule), info_(make_info(rule)) {}
  const SchemeInfo& info() const override { return info_; }

  std::optional<std::string> unsupported(const RunRequest& r) const override {
    return refined::unsupported_request(r, info_.name);
  }

  std::unique_ptr<Evaluation> prepare(const ControlMesh& mesh, const RunRequest& r) const override {
    return make_evaluation(mesh, rule_, r, true);
  }

 private:
  SubdivisionRule rule_;
  SchemeInfo info_;
};

std::vector<std::unique_ptr<Scheme>> make_halfedge_schemes() {
  std::vector<std::unique_ptr<Scheme>> s;
  s.push_back(std::make_unique<HalfedgeScheme>(SubdivisionRule::CatmullClark));
  s.push_back(std::make_unique<HalfedgeScheme>(SubdivisionRule::Loop));
  return s;
}

SDB_REGISTER_SCHEMES(halfedge, make_halfedge_schemes);

}  // namespace

std::unique_ptr<Evaluation> make_evaluation(const ControlMesh& mesh, SubdivisionRule rule, const RunRequest& r,
                                            bool project_to_limit) {
  check_size(mesh, rule, r.level);
  if (r.backend == Backend::Vulkan) return make_vulkan_evaluation(mesh, rule, r.level, project_to_limit);
  return make_cpu_evaluation(mesh, rule, r.level, r.backend == Backend::CpuMt, r.threads, project_to_limit);
}

}  // namespace sdb::halfedge
