#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/refined/requests.h"
#include "schemes/edgefriend/edgefriend.h"
#include "schemes/edgefriend/surface.h"
#include "schemes/edgefriend/vulkan.h"

namespace sdb::edgefriend {
namespace {

SchemeInfo make_info() {
  SchemeInfo info;
  info.name = "edgefriend-cc";
  info.paper = "Kuth, Oberberger, Chajdas, Meyer 2023, Edge-Friend: Fast and Deterministic Catmull-Clark Subdivision Surfaces (HPG)";
  info.description =
      "peer: Edge-Friend refinement to depth k (a first Catmull-Clark step, then one kernel a level over faces and vertices, "
      "no atomics) with OpenSubdiv's crease rules (the paper's vertex rule differs at some semi-sharp vertices), "
      "limit projection with Far's masks";
  info.role = SchemeRole::Peer;
  info.reference = SubdivisionRule::CatmullClark;
  info.level_kind = LevelKind::Depth;
  // Measured 194 bytes per output triangle at a validated run's peak (the sword, validate at
  // depths 2 and 3); a bench's peak at depth 4 is 111 on cpu, cpu-mt and vulkan
  // (../halfedge/notes/2026-12-07-limit.md). On lavapipe the device's buffers are the process's
  // memory too: halfedge-cc's validated Vulkan run at the sword's depth 5 took 279 bytes a triangle
  // (../halfedge/notes/2026-12-08-issues-size.md), and this frame is the same (harness/refined).
  // 336 leaves a fifth over that.
  info.peak_bytes_per_triangle = 336;
  info.backends = {Backend::Cpu, Backend::CpuMt, Backend::Vulkan};
  info.default_levels = {1, 2, 3, 4};
  info.accepts.faces = MeshRequirements::Faces::Any;  // the first step makes quads of every face
  info.accepts.manifold = true;                        // a quad has one friend across each edge
  info.accepts.creases = true;
  info.accepts.holes = false;
  // Judged as osd-uniform, whose refinement and limit masks these equal: without a bound, and
  // approximating where a semi-sharp crease outlasts the depth (Far's masks take it as infinite).
  info.limit = LimitClaim::ReproducesOnceSharpnessDecays;
  info.peer = "osd-uniform";
  info.default_meshes = {"stein/sword_quad_dominant", "crane/spot_control", "pmp/fandisk_quads"};
  info.headline_runs = {{"stein/sword_quad_dominant", Backend::CpuMt, 4}};
  return info;
}

class EdgeFriendScheme final : public Scheme {
 public:
  EdgeFriendScheme() : info_(make_info()) {}
  const SchemeInfo& info() const override { return info_; }

  std::optional<std::string> unsupported(const RunRequest& r) const override {
    return refined::unsupported_request(r, info_.name);
  }

  std::unique_ptr<Evaluation> prepare(const ControlMesh& mesh, const RunRequest& r) const override {
    return make_evaluation(mesh, r, true);
  }

 private:
  SchemeInfo info_;
};

std::vector<std::unique_ptr<Scheme>> make_edgefriend_schemes() {
  std::vector<std::unique_ptr<Scheme>> s;
  s.push_back(std::make_unique<EdgeFriendScheme>());
  return s;
}

SDB_REGISTER_SCHEMES(edgefriend, make_edgefriend_schemes);

}  // namespace

std::unique_ptr<Evaluation> make_evaluation(const ControlMesh& mesh, const RunRequest& r, bool project_to_limit) {
  check_size(mesh, r.level);
  if (r.backend == Backend::Vulkan) return make_vulkan_evaluation(mesh, r.level, project_to_limit);
  return make_cpu_evaluation(mesh, r.level, r.backend == Backend::CpuMt, r.threads, project_to_limit);
}

}  // namespace sdb::edgefriend
