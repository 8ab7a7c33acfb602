// The geometry-image schemes: "geometry-image" (fused passes, the default) and
// "geometry-image-permask" (one pass per mask, as the paper's Radeon implementation). prepare()
// finds or creates the image and hands its closed mesh g0 to the backend (backends.h).
#include <cstdlib>
#include <string>

#include "backends.h"
#include "closed_mesh.h"
#include "creation/create.h"
#include "errors.h"
#include "geometry_image.h"

namespace sdb {

namespace {

using namespace gim;

constexpr int kMaxLevel = 6;
// Output vertices beyond this would need more than a few GiB for buffers, positions and indices.
constexpr long long kMaxOutputVertices = 1ll << 26;

class GeometryImageScheme final : public Scheme {
 public:
  explicit GeometryImageScheme(const GeometryImageOptions& options) : options_(options) {
    const bool per_mask = options.plan == PassPlan::PerMask;
    info_.name = geometry_image_scheme_name(options.plan);
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
    const long n = image ? image->size : resolved_fit_size(options_);
    const long side = (n - 1) << request.level;
    return 2 * side * side;
  }

  std::unique_ptr<Evaluation> prepare(const ControlMesh& mesh, const RunRequest& request) const override {
    if (auto why = unsupported(request)) throw InputError(mesh.name, *why);
    GeometryImage image = select_image(mesh);
    const long long n = level_size(image.size, request.level);
    if (n * n > kMaxOutputVertices)
      throw InputError(mesh.name, "a " + std::to_string(image.size) + " x " + std::to_string(image.size) +
                                      " image at depth " + std::to_string(request.level) + " gives " +
                                      std::to_string(n * n) + " vertices, more than this scheme allocates");
    EvaluationInput input;
    input.g0 = std::make_shared<const ControlMesh>(closed_mesh(image, mesh.name + " (g0)", mesh.source));
    input.base_size = image.size;
    input.request = request;
    input.plan = options_.plan;
    if (request.backend == Backend::Vulkan) return make_vulkan_evaluation(input, mesh.name);
    return make_cpu_evaluation(input);
  }

 private:
  // The mesh is an image's g0 (taken as is), or a surface to fit an image of fit_size to.
  GeometryImage select_image(const ControlMesh& mesh) const {
    if (auto image = image_from_closed_mesh(mesh)) return std::move(*image);
    CreationOptions creation;
    creation.size = resolved_fit_size(options_);
    return create_geometry_image(mesh, creation).image;
  }

  GeometryImageOptions options_;
  SchemeInfo info_;
};

}  // namespace

std::string geometry_image_scheme_name(gim::PassPlan plan) {
  return plan == gim::PassPlan::PerMask ? "geometry-image-permask" : "geometry-image";
}

int resolved_fit_size(const GeometryImageOptions& options) {
  if (options.fit_size != 0) return options.fit_size;
  const char* env = std::getenv("SUBDIVBENCH_GIM_SIZE");
  if (!env || !*env) return kDefaultFitSize;
  char* end = nullptr;
  const long n = std::strtol(env, &end, 10);
  if (*end != '\0' || n < 5 || n > 1025 || n % 2 == 0)
    throw InputError("SUBDIVBENCH_GIM_SIZE", "must be an odd number from 5 to 1025, not '" + std::string(env) + "'");
  return static_cast<int>(n);
}

std::unique_ptr<Scheme> make_geometry_image_scheme(const GeometryImageOptions& options) {
  return std::make_unique<GeometryImageScheme>(options);
}

}  // namespace sdb
