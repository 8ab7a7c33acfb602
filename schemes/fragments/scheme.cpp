#include <cstdio>
#include <string>

#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "schemes/fragments/cpu.h"
#include "schemes/fragments/fragments.h"
#include "schemes/fragments/vulkan.h"

namespace sdb::fragments {
namespace {

constexpr int kMaxDepth = 8;
// Positions and normals of the output; past this a request is refused before anything is built.
constexpr double kMaxOutputBytes = 8e9;

SchemeInfo make_info(SubdivisionRule rule) {
  const bool loop = rule == SubdivisionRule::Loop;
  SchemeInfo info;
  info.name = loop ? "fragments-loop" : "fragments-cc";
  info.paper = "Shiue, Jones, Peters 2005, A realtime GPU subdivision kernel; Loop with mesh fragments (poster)";
  info.description = loop ? "Loop mesh fragments refined through pattern tables, limit projection"
                          : "Catmull-Clark mesh fragments refined through pattern tables, limit projection";
  info.role = SchemeRole::Method;
  info.reference = rule;
  info.level_kind = LevelKind::Depth;
  // Measured 171 (fragments-cc) and 181 (mipgh-cc) bytes per output triangle at a validated run's
  // peak (harness/bench/notes/limits-2026-12-07.md); 256 leaves two fifths to spare.
  info.peak_bytes_per_triangle = 256;
  info.backends = {Backend::Cpu, Backend::CpuMt, Backend::Vulkan};
  info.default_levels = {1, 2, 3, 4};
  info.accepts.faces = loop ? MeshRequirements::Faces::TrianglesOnly : MeshRequirements::Faces::QuadsOnly;
  info.accepts.quadrangulate = !loop;
  info.accepts.manifold = true;
  info.accepts.creases = true;
  info.accepts.holes = true;
  // Positions: 1e-5 of the diagonal (the default set's worst: 7.9e-7, gim-sphere-31's valence-2
  // vertices). Normals: 0.01 degrees, taken from the control points (net_tangents.cpp) so that
  // float's rounding does not grow with the depth, and from the ring's eigenvectors where Far's
  // masks are not the limit (ring_limit.h).
  info.bound = {1e-5, 0.01};
  // Depth schemes are read against OpenSubdiv's uniform refinement at the same depth.
  info.peer = loop ? "osd-uniform-loop" : "osd-uniform";
  info.default_meshes = loop ? std::vector<std::string>{"stanford/bunny", "crane/spot_low_resolution",
                                                        "pmp/icosahedron_subdiv"}
                             : std::vector<std::string>{"stein/sword_quad_dominant", "crane/spot_control",
                                                        "pmp/fandisk_quads"};
  info.headline_runs = {{loop ? "stanford/bunny" : "stein/sword_quad_dominant", Backend::Cpu, 4},
                        {loop ? "stanford/bunny" : "stein/sword_quad_dominant", Backend::CpuMt, 4}};
  return info;
}

class FragmentScheme final : public Scheme {
 public:
  explicit FragmentScheme(SubdivisionRule rule) : rule_(rule), info_(make_info(rule)) {}
  const SchemeInfo& info() const override { return info_; }

  std::optional<std::string> unsupported(const RunRequest& r) const override {
    if (r.level < 0 || r.level > kMaxDepth) return "depth must be 0.." + std::to_string(kMaxDepth);
    if (r.backend == Backend::Vulkan) return vulkan_unavailable();
    if (r.backend != Backend::Cpu && r.backend != Backend::CpuMt)
      return info_.name + " runs on cpu, cpu-mt and vulkan";
    return std::nullopt;
  }

  std::unique_ptr<Evaluation> prepare(const ControlMesh& mesh, const RunRequest& r) const override {
    return make_evaluation(mesh, rule_, r);
  }

 private:
  SubdivisionRule rule_;
  SchemeInfo info_;
};

std::vector<std::unique_ptr<Scheme>> make_fragment_schemes() {
  std::vector<std::unique_ptr<Scheme>> s;
  s.push_back(std::make_unique<FragmentScheme>(SubdivisionRule::CatmullClark));
  s.push_back(std::make_unique<FragmentScheme>(SubdivisionRule::Loop));
  return s;
}

SDB_REGISTER_SCHEMES(fragments, make_fragment_schemes);

}  // namespace

std::unique_ptr<Evaluation> make_evaluation(const ControlMesh& mesh, SubdivisionRule rule, const RunRequest& r,
                                            bool project_to_limit) {
  const double bytes = static_cast<double>(output_vertices(mesh, rule, r.level)) * 2 * sizeof(Point3);
  if (bytes > kMaxOutputBytes || bytes / (2 * sizeof(Point3)) >= 4294967295.0) {
    char why[160];
    std::snprintf(why, sizeof why, "depth %d would write %.1f GB of positions and normals, past the %.0f GB limit",
                  r.level, bytes / 1e9, kMaxOutputBytes / 1e9);
    throw Unsupported(why);
  }
  if (r.backend == Backend::Vulkan) return make_vulkan_evaluation(mesh, rule, r.level, project_to_limit);
  return std::make_unique<CpuFragmentEvaluation>(mesh, rule, r.level, r.backend == Backend::CpuMt, r.threads,
                                                 project_to_limit);
}

FragmentStats stats_of(const Evaluation& e) {
  if (auto* cpu = dynamic_cast<const CpuFragmentEvaluation*>(&e)) return cpu->surface().stats();
  if (auto s = vulkan_stats(e)) return *s;
  return {};
}

}  // namespace sdb::fragments
