// The geometry-image scheme on the CPU: prepare() finds or creates the image and sizes every
// buffer; execute() runs the Subdivider's passes on one thread (cpu) or on TBB's (cpu-mt).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <cstdlib>
#include <string>

#include "closed_mesh.h"
#include "creation/create.h"
#include "errors.h"
#include "geometry_image.h"
#include "tessellation_grid.h"

namespace sdb {

namespace {

using namespace gim;

constexpr int kMaxLevel = 6;
// Output vertices beyond this would need more than a few GiB for buffers, positions and indices.
constexpr long long kMaxOutputVertices = 1ll << 26;

// cpu-mt: rows in blocks of a few, each block computed exactly as the serial pass computes it.
class TbbRows final : public RowExecutor {
 public:
  explicit TbbRows(int threads) : arena_(threads > 0 ? threads : tbb::task_arena::automatic) {}
  void for_rows(int rows, RowBody body) const override {
    arena_.execute([&] {
      tbb::parallel_for(tbb::blocked_range<int>(0, rows, 4),
                        [&](const tbb::blocked_range<int>& r) { body({r.begin(), r.end()}); });
    });
  }

 private:
  mutable tbb::task_arena arena_;
};

class CpuEvaluation final : public Evaluation {
 public:
  CpuEvaluation(std::shared_ptr<const ControlMesh> g0, int base_size, const RunRequest& request, PassPlan plan)
      : g0_(std::move(g0)), subdivider_(base_size, request.level, plan) {
    if (request.backend == Backend::CpuMt)
      rows_ = std::make_unique<TbbRows>(request.threads);
    else
      rows_ = std::make_unique<SerialRows>();
    const int n = subdivider_.size(request.level);
    out_.positions.resize(static_cast<size_t>(n) * n);
    out_.normals.resize(out_.positions.size());
    out_.triangles = grid_triangles(n);
    out_.coords = grid_coords(base_size, request.level);
    out_.reference = g0_;
  }

  void execute() override { subdivider_.run(g0_->positions.data(), out_.positions.data(), out_.normals.data(), *rows_); }
  const Tessellation& result() override { return out_; }
  size_t bytes_out() const override { return out_.positions.size() * 2 * sizeof(Point3); }

 private:
  std::shared_ptr<const ControlMesh> g0_;
  Subdivider subdivider_;
  std::unique_ptr<RowExecutor> rows_;
  Tessellation out_;
};

class GeometryImageScheme final : public Scheme {
 public:
  explicit GeometryImageScheme(const GeometryImageOptions& options) : options_(options) {
    info_.name = "geometry-image";
    info_.paper = "Losasso, Hoppe, Schaefer, Warren 2003: Smooth Geometry Images";
    info_.description = "one bicubic B-spline patch stored as a geometry image, subdivided by image masks";
    info_.reference = SubdivisionRule::CatmullClark;
    info_.level_kind = LevelKind::Depth;
    info_.backends = {Backend::Cpu, Backend::CpuMt};
    info_.default_levels = {1, 2, 3, 4};
    info_.accepts.faces = MeshRequirements::Faces::Any;
    info_.accepts.manifold = true;
    info_.accepts.closed = true;
    info_.accepts.genus0 = true;
  }

  const SchemeInfo& info() const override { return info_; }

  std::optional<std::string> unsupported(const RunRequest& r) const override {
    if (r.level < 0 || r.level > kMaxLevel) return "depth must be 0.." + std::to_string(kMaxLevel);
    if (r.backend == Backend::Vulkan) return "the Vulkan variant is not built yet";
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
    auto g0 = std::make_shared<const ControlMesh>(closed_mesh(image, mesh.name + " (g0)", mesh.source));
    return std::make_unique<CpuEvaluation>(std::move(g0), image.size, request, options_.plan);
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
