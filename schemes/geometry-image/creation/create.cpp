#include "schemes/geometry-image/creation/create.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "harness/core/errors.h"
#include "schemes/geometry-image/creation/surface_sampler.h"

namespace sdb::gim {

namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

uint64_t mix_key(uint64_t h, const std::string& text) {
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace

GeometryImageCreator::GeometryImageCreator(const ControlMesh& mesh, CreationOptions options)
    : mesh_(mesh), options_(std::move(options)) {
  require_closed_genus0(mesh_);
  surface_ = triangulate(mesh_);
  domains_ = face_domains(mesh_, surface_.triangles);
}

GeometryImageCreator::~GeometryImageCreator() = default;

uint64_t GeometryImageCreator::cache_key() const {
  const SphericalParametrizationOptions& p = options_.parametrization;
  char settings[256];
  std::snprintf(settings, sizeof settings,
                "gim-create-v%d fairness=%.9g reprojections=%d tris=%zu rounds=%d inverse=%.9g sweeps=%d tol=%.9g",
                kCreationVersion, options_.fit.fairness, options_.fit.reprojections, p.min_triangles, p.reweighting_rounds, p.inverse_weight, p.max_sweeps,
                p.tolerance);
  return mix_key(content_hash(mesh_), settings);
}

const SphericalParametrization& GeometryImageCreator::parametrization() {
  if (!parametrization_) {
    const auto start = std::chrono::steady_clock::now();
    parametrization_ = SphericalParametrization::compute(surface_, options_.parametrization);
    parametrize_ms_ = ms_since(start);
    if (parametrization_->folded_triangles > 0) {
      const std::string count = std::to_string(parametrization_->folded_triangles) + " of " +
                                std::to_string(parametrization_->surface.triangles.size());
      throw InputError(mesh_.source.empty() ? mesh_.name : mesh_.source,
                       "geometry-image creation could not embed '" + mesh_.name + "' in the sphere: " + count +
                           " triangles collapse in its Tutte embedding (a shape this elongated needs a "
                           "parametrization method that this scheme does not have)");
    }
  }
  return *parametrization_;
}

const LimitEvaluator& GeometryImageCreator::limit() {
  if (!limit_) limit_ = std::make_unique<LimitEvaluator>(mesh_, SubdivisionRule::CatmullClark);
  return *limit_;
}

const LimitProjector& GeometryImageCreator::projector() {
  if (!projector_) projector_ = std::make_unique<LimitProjector>(limit());
  return *projector_;
}

DenseSamples sample_limit_surface(const SphericalParametrization& parametrization, const FaceDomains& domains,
                                  const LimitEvaluator& limit, int n) {
  FaceDomains refined = domains;
  while (refined.face.size() < parametrization.surface.triangles.size()) refined = refine_domains(refined);
  if (refined.face.size() != parametrization.surface.triangles.size())
    throw std::logic_error("sample_limit_surface: the domains are not those of the parametrized surface's triangles");
  const ControlMesh& mesh = limit.mesh();
  const SurfaceSampler sampler(parametrization.surface, parametrization.sphere);
  DenseSamples samples;
  samples.side = dense_sample_side(n);
  samples.points.resize(static_cast<size_t>(samples.side) * samples.side);
  const double to_image = static_cast<double>(n - 1) / (samples.side - 1);
  tbb::parallel_for(tbb::blocked_range<int>(0, samples.side), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j < rows.end(); ++j)
      for (int i = 0; i < samples.side; ++i) {
        const SurfaceSampler::Location at =
            sampler.locate(OctahedralMap::sphere_from_image(i * to_image, j * to_image, n));
        const auto& [a, b, c] = refined.corners[at.triangle];
        const double w0 = 1.0 - at.b1 - at.b2;
        const Vec2d domain{w0 * a[0] + at.b1 * b[0] + at.b2 * c[0], w0 * a[1] + at.b1 * b[1] + at.b2 * c[1]};
        const int face = refined.face[at.triangle];
        const LimitSample s =
            limit.evaluate(domain_coord(mesh.face_sizes[face], limit.first_ptex_face(face), domain));
        samples.points[static_cast<size_t>(j) * samples.side + i] = s.position;
      }
  });
  return samples;
}

CreatedImage GeometryImageCreator::create(int size) {
  const CutSymmetry check(size);  // validates the size
  const ImageCache cache(options_.cache_dir.empty() ? ImageCache::default_directory() : options_.cache_dir);
  const uint64_t key = cache_key();
  std::string refused;
  if (options_.use_cache)
    if (auto cached = cache.load(key, size, &refused)) {
      CreatedImage out{std::move(cached->image), {}};
      CreationReport& r = out.report;
      r.from_cache = true;
      r.cache_path = cached->path;
      auto figure = [&](const char* name) { return cached->figures.count(name) ? cached->figures.at(name) : 0.0; };
      r.parametrize_ms = figure("parametrize_ms"), r.sample_ms = figure("sample_ms"), r.fit_ms = figure("fit_ms");
      r.stretch = figure("stretch"), r.rms_residual = figure("rms_residual");
      r.cg_iterations = static_cast<int>(figure("cg_iterations"));
      r.unknowns = static_cast<int>(figure("unknowns"));
      r.samples = static_cast<long>(figure("samples"));
      return out;
    }

  CreatedImage out;
  CreationReport& r = out.report;
  r.cache_refused = refused;
  const SphericalParametrization& param = parametrization();
  r.parametrize_ms = parametrize_reported_ ? 0.0 : parametrize_ms_;
  parametrize_reported_ = true;
  r.stretch = param.stretch;
  auto start = std::chrono::steady_clock::now();
  const DenseSamples samples = sample_limit_surface(param, domains_, limit(), size);
  r.sample_ms = ms_since(start);
  start = std::chrono::steady_clock::now();
  FitReport fit;
  const LimitProjector& onto = projector();
  // The fitted patch lies within a few thousandths of the diagonal of the surface: the search starts there.
  const double hint = 0.01 * onto.diagonal();
  out.image = fit_geometry_image(size, samples, options_.fit, &fit,
                                 [&](const Vec3d& p) { return onto.closest(p, hint).limit.position; });
  r.fit_ms = ms_since(start);
  r.cg_iterations = fit.iterations;
  r.rms_residual = fit.rms_residual;
  r.unknowns = fit.unknowns;
  r.samples = fit.samples;
  if (options_.use_cache)
    r.cache_path = cache.store(key, out.image,
                               {{"parametrize_ms", parametrize_ms_},
                                {"sample_ms", r.sample_ms},
                                {"fit_ms", r.fit_ms},
                                {"stretch", r.stretch},
                                {"rms_residual", r.rms_residual},
                                {"cg_iterations", r.cg_iterations},
                                {"unknowns", r.unknowns},
                                {"samples", static_cast<double>(r.samples)}});
  return out;
}

CreatedImage create_geometry_image(const ControlMesh& mesh, const CreationOptions& options) {
  GeometryImageCreator creator(mesh, options);
  return creator.create(options.size);
}

}  // namespace sdb::gim
