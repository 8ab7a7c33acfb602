#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "schemes/cpatch/cpatch.h"

#include "schemes/cpatch/cpu.h"
#include "schemes/cpatch/vulkan.h"

namespace sdb {
namespace {

constexpr const char* kPaper = "Ni, Yeo, Myles, Goel, Peters 2008, GPU Smoothing of Quad Meshes";

// Section 1: any polygon mesh becomes a quad mesh by one Catmull-Clark step; Section 2 needs
// every vertex surrounded by quads, hence closed; creases and holes are not part of the paper.
MeshRequirements cpatch_requirements() {
  MeshRequirements r;
  r.faces = MeshRequirements::Faces::QuadsOnly;
  r.quadrangulate = true;
  r.manifold = true;
  r.closed = true;
  r.creases = false;
  r.holes = false;
  return r;
}

SchemeInfo make_info(const char* name, const char* description, std::vector<Backend> backends,
                     std::vector<int> levels) {
  SchemeInfo info;
  info.name = name;
  info.paper = kPaper;
  info.description = description;
  info.reference = SubdivisionRule::CatmullClark;
  info.level_kind = LevelKind::Rate;
  info.backends = std::move(backends);
  info.default_levels = std::move(levels);
  info.accepts = cpatch_requirements();
  info.peer = "osd-bfr";  // the same rate N on the same mesh
  // An approximation of the Catmull-Clark limit (the paper's Figure 12): at most 1.15% of the
  // diagonal (pole8) and 43 degrees (next to Blub's extraordinary vertices) in the default set.
  info.bound = {0.02, 60};
  info.limit = LimitClaim::Approximates;
  // The paper's models (stood in for, TABLES.md) and the real meshes its issue names.
  info.default_meshes = {"sword-standin",      "head-standin",       "frog-standin",
                         "crane/spot_control", "crane/blub_control", "pmp/fandisk_quads"};
  // The 22k-quad sword (89,512 quads after the Catmull-Clark step): N = 10 gives 14.5 M triangles.
  info.large_meshes = {"stein/sword_quad_dominant"};
  return info;
}

std::optional<std::string> rate_unsupported(int rate) {
  if (rate < 2) return "rate N = " + std::to_string(rate) + " is below 2 (N x N samples per quad)";
  return std::nullopt;
}

class CpatchTwoPassScheme final : public Scheme {
 public:
  const SchemeInfo& info() const override { return cpatch_2pass_info(); }

  std::optional<std::string> unsupported(const RunRequest& request) const override {
    if (request.backend == Backend::Vulkan)
      return cpatch::vulkan_unsupported(cpatch::GpuVariant::TwoPass, cpatch::GpuMode::Evaluate, request.level);
    return rate_unsupported(request.level);
  }

  std::unique_ptr<Evaluation> prepare(const ControlMesh& mesh, const RunRequest& request) const override {
    if (auto why = rate_unsupported(request.level)) throw InputError(mesh.name, *why);
    if (request.backend == Backend::Vulkan)
      return std::make_unique<cpatch::CpatchVulkanEvaluation>(mesh, request.level, cpatch::GpuVariant::TwoPass);
    return std::make_unique<cpatch::CpatchCpuEvaluation>(mesh, request.level, request.backend == Backend::CpuMt,
                                                         request.threads);
  }
};

// cpatch-1pass and cpatch-tess: Vulkan only.
class CpatchGpuOnlyScheme final : public Scheme {
 public:
  CpatchGpuOnlyScheme(const SchemeInfo& info, cpatch::GpuVariant variant) : info_(info), variant_(variant) {}
  const SchemeInfo& info() const override { return info_; }

  std::optional<std::string> unsupported(const RunRequest& request) const override {
    if (request.backend != Backend::Vulkan)
      return info_.name + " runs on the vulkan backend only (its amplification is a shader stage's)";
    return cpatch::vulkan_unsupported(variant_, cpatch::GpuMode::Evaluate, request.level);
  }

  std::unique_ptr<Evaluation> prepare(const ControlMesh& mesh, const RunRequest& request) const override {
    if (request.backend != Backend::Vulkan) throw InputError(mesh.name, *unsupported(request));
    return std::make_unique<cpatch::CpatchVulkanEvaluation>(mesh, request.level, variant_);
  }

 private:
  const SchemeInfo& info_;
  cpatch::GpuVariant variant_;
};

}  // namespace

const SchemeInfo& cpatch_2pass_info() {
  static const SchemeInfo info = [] {
    SchemeInfo i = make_info(
        "cpatch-2pass", "bicubic patches on ordinary quads, c-patches on extraordinary ones; convert, then evaluate",
        {Backend::Cpu, Backend::CpuMt, Backend::Vulkan}, {2, 5, 9, 17, 33});
    // The README's headline: the 22k-quad sword at N = 9, one thread and all, against osd-bfr.
    i.headline_runs = {{"stein/sword_quad_dominant", Backend::Cpu, 9}, {"stein/sword_quad_dominant", Backend::CpuMt, 9}};
    return i;
  }();
  return info;
}

const SchemeInfo& cpatch_1pass_info() {
  static const SchemeInfo info =
      make_info("cpatch-1pass", "c-patches converted and evaluated in one geometry-shader pass (paper: N <= 8)",
                {Backend::Vulkan}, {2, 5, 8});
  return info;
}

const SchemeInfo& cpatch_tess_info() {
  static const SchemeInfo info =
      make_info("cpatch-tess", "c-patches evaluated by the hardware tessellator (the paper's Section 6 outlook)",
                {Backend::Vulkan}, {2, 5, 9, 17, 33});
  return info;
}

std::vector<std::unique_ptr<Scheme>> make_cpatch_schemes() {
  std::vector<std::unique_ptr<Scheme>> schemes;
  schemes.push_back(std::make_unique<CpatchTwoPassScheme>());
  schemes.push_back(std::make_unique<CpatchGpuOnlyScheme>(cpatch_1pass_info(), cpatch::GpuVariant::OnePass));
  schemes.push_back(std::make_unique<CpatchGpuOnlyScheme>(cpatch_tess_info(), cpatch::GpuVariant::Tessellation));
  return schemes;
}

SDB_REGISTER_SCHEMES(cpatch, make_cpatch_schemes);

}  // namespace sdb
