// The geometry-image schemes: "geometry-image" (fused passes, the default) and
// "geometry-image-permask" (one pass per mask, as the paper's Radeon implementation). prepare()
// finds or creates the image and hands its closed mesh g0 to the backend (backends.h).
#include <memory>
#include <string>
#include <vector>

#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "schemes/geometry-image/analytic.h"
#include "schemes/geometry-image/backends.h"
#include "schemes/geometry-image/closed_mesh.h"
#include "schemes/geometry-image/creation/create.h"
#include "schemes/geometry-image/geometry_image.h"

namespace sdb {

namespace {

using namespace gim;

constexpr int kMaxLevel = 6;
// Output vertices beyond this would need more than a few GiB for buffers, positions and indices.
constexpr long long kMaxOutputVertices = 1ll << 26;

// An evaluation with what its row should say of how its image was made (Evaluation::notes).
class NotedEvaluation final : public Evaluation {
 public:
  NotedEvaluation(std::unique_ptr<Evaluation> inner, std::vector<std::string> notes)
      : inner_(std::move(inner)), notes_(std::move(notes)) {}
  void execute() override { inner_->execute(); }
  const Tessellation& result() override { return inner_->result(); }
  size_t bytes_out() const override { return inner_->bytes_out(); }
  std::optional<GpuTimes> gpu_times() const override { return inner_->gpu_times(); }
  std::vector<std::string> notes() const override { return notes_; }

 private:
  std::unique_ptr<Evaluation> inner_;
  std::vector<std::string> notes_;
};

class GeometryImageScheme final : public Scheme {
 public:
  explicit GeometryImageScheme(PassPlan plan) : plan_(plan) {
    const bool per_mask = plan == PassPlan::PerMask;
    info_.name = geometry_image_scheme_name(plan);
    info_.paper = "Losasso, Hoppe, Schaefer, Warren 2003: Smooth Geometry Images";
    info_.description = per_mask ? "geometry image subdivided one pass per mask (L, A, E, T), as the paper's GPU"
                                 : "one bicubic B-spline patch stored as a geometry image, subdivided by image masks";
    info_.reference = SubdivisionRule::CatmullClark;
    info_.level_kind = LevelKind::Depth;
    info_.backends = {Backend::Cpu, Backend::CpuMt, Backend::Vulkan};
    info_.default_levels = {1, 2, 3, 4};
    info_.accepts.faces = MeshRequirements::Faces::Any;
    info_.accepts.manifold = true;
    info_.accepts.closed = true;
    info_.accepts.genus0 = true;
    // osd-bfr at the same segments per edge on the same mesh (on an analytic image's g0, the same
    // surface); the paper's own comparison, osd-uniform on the same g0, is losasso2003-table2.
    info_.peer = "osd-bfr";
    // The image is fitted to the input's Catmull-Clark limit surface (creation/): the output
    // approximates it, measured by nearest points; the figures are reported.
    info_.limit = LimitClaim::Approximates;
    // Against the Catmull-Clark limit of its own g0 at the output's coords (the scheme's exactness):
    // 1e-7 of the diagonal away from the four cut vertices, 0.13% next to them (Spot, depth 1),
    // normals up to 41 degrees there (Blub).
    info_.own_bound = {0.005, 60};
    info_.default_meshes = {"gim-sphere-31", "crane/spot_control", "crane/blub_control", "stanford/bunny"};
    // The output grows with the image, not the mesh, and depth 6 is the largest: a 63 x 63 image
    // reaches 31.5 M triangles there (the 31 x 31 one 7.4 M), with no fitting to do.
    info_.large_meshes = {"gim-sphere-63"};
    info_.parameters = {fit_size_parameter()};
  }

  const SchemeInfo& info() const override { return info_; }

  std::optional<std::string> unsupported(const RunRequest& r) const override {
    if (r.level < 0 || r.level > kMaxLevel) return "depth must be 0.." + std::to_string(kMaxLevel);
    if (r.backend == Backend::Vulkan) return vulkan_unavailable();
    return std::nullopt;
  }

  // The output is the image subdivided, whatever the input's size: 2 ((n - 1) 2^k)^2 triangles.
  long estimated_triangles(const ControlMesh& mesh, const RunRequest& request) const override {
    const auto image = image_from_closed_mesh(mesh);
    const long n = image ? image->size : request.parameters.integer("fit");
    const long side = (n - 1) << request.level;
    return 2 * side * side;
  }

  // Fitting an image to a mesh that is not one (creation/) holds about 8 KiB per sample at its
  // peak: measured 1.9 GB more than reading the cached image at 513 x 513 (cube, 2026-12-07).
  // Counted whether or not the image is cached: the estimate does not read the disk.
  double estimated_peak_bytes(const ControlMesh& mesh, const RunRequest& request) const override {
    constexpr double kFitBytesPerSample = 8192;
    const double fit = image_from_closed_mesh(mesh) ? 0.0 : double(request.parameters.integer("fit"));
    return Scheme::estimated_peak_bytes(mesh, request) + fit * fit * kFitBytesPerSample;
  }

  std::unique_ptr<Evaluation> prepare(const ControlMesh& mesh, const RunRequest& request) const override {
    if (auto why = unsupported(request)) throw InputError(mesh.name, *why);
    std::vector<std::string> notes;
    GeometryImage image = select_image(mesh, request.parameters.integer("fit"), notes);
    const long long n = level_size(image.size, request.level);
    if (n * n > kMaxOutputVertices)
      throw Unsupported(mesh.name + ": a " + std::to_string(image.size) + " x " + std::to_string(image.size) +
                                      " image at depth " + std::to_string(request.level) + " gives " +
                                      std::to_string(n * n) + " vertices, more than this scheme allocates");
    EvaluationInput input;
    input.g0 = std::make_shared<const ControlMesh>(closed_mesh(image, mesh.name + " (g0)", mesh.source));
    input.base_size = image.size;
    input.request = request;
    input.plan = plan_;
    auto evaluation = request.backend == Backend::Vulkan ? make_vulkan_evaluation(input, mesh.name) : make_cpu_evaluation(input);
    if (notes.empty()) return evaluation;
    return std::make_unique<NotedEvaluation>(std::move(evaluation), std::move(notes));
  }

 private:
  // The mesh is an image's g0 (taken as is), or a surface to fit an image of `fit` samples a side
  // to; a cached fit refused on reading (cache.h) is refitted, and `notes` says so.
  static GeometryImage select_image(const ControlMesh& mesh, int fit, std::vector<std::string>& notes) {
    if (auto image = image_from_closed_mesh(mesh)) return std::move(*image);
    CreationOptions creation;
    creation.size = fit;
    CreatedImage created = create_geometry_image(mesh, creation);
    if (!created.report.cache_refused.empty())
      notes.push_back("cached geometry image refused (" + created.report.cache_refused + "): refitted");
    return std::move(created.image);
  }

  PassPlan plan_;
  SchemeInfo info_;
};

}  // namespace

std::string geometry_image_scheme_name(gim::PassPlan plan) {
  return plan == gim::PassPlan::PerMask ? "geometry-image-permask" : "geometry-image";
}

ParameterSpec fit_size_parameter() {
  // At most 513: fitting 513 x 513 took 80 s and 2.7 GB here (2026-12-07, a loaded machine); 1025,
  // four times the samples, ran for minutes and ended in bad_alloc under 6 GiB.
  return {"fit", "samples a side of the image fitted to a mesh that is not one", true, kDefaultFitSize, 5, 513, 2};
}

std::unique_ptr<Scheme> make_geometry_image_scheme(PassPlan plan) { return std::make_unique<GeometryImageScheme>(plan); }

std::vector<std::unique_ptr<Scheme>> make_geometry_image_schemes() {
  std::vector<std::unique_ptr<Scheme>> schemes;
  schemes.push_back(make_geometry_image_scheme(PassPlan::Fused));
  schemes.push_back(make_geometry_image_scheme(PassPlan::PerMask));
  return schemes;
}

namespace {

// gim-sphere-31 and gim-ellipsoid-31 by name, any odd size through gim-sphere-<n>.
MeshProvider analytic_meshes() {
  MeshProvider p;
  p.builtins = {
      {"gim-sphere-31", "geometry image 31x31 of the unit sphere: its closed control mesh g0 (the paper's Table 2 size)",
       [] { return *gim::analytic_mesh_from_name("gim-sphere-31"); }},
      {"gim-ellipsoid-31", "geometry image 31x31 of an ellipsoid (radii 1.2, 0.8, 0.6): its control mesh g0",
       [] { return *gim::analytic_mesh_from_name("gim-ellipsoid-31"); }},
  };
  p.parse = [](const std::string& name) { return gim::analytic_mesh_from_name(name); };
  return p;
}

}  // namespace

SDB_REGISTER_SCHEMES(geometry_image, make_geometry_image_schemes);
SDB_REGISTER_MESHES(geometry_image, analytic_meshes);

}  // namespace sdb
