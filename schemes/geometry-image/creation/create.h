// Geometry image creation (Section 4): spherical parametrization, the octahedral map unfolded by
// the X-cut, dense sampling of the input's Catmull-Clark limit surface through them (FaceDomains
// carries a point of the triangulated input to its face's ptex coordinate), and the least-squares
// fit of the image's patch to those samples; results are cached on disk (cache.h).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "harness/core/control_mesh.h"
#include "harness/reference/limit_evaluator.h"
#include "harness/validate/limit_projector.h"
#include "schemes/geometry-image/creation/cache.h"
#include "schemes/geometry-image/creation/face_domains.h"
#include "schemes/geometry-image/creation/fit.h"
#include "schemes/geometry-image/creation/parametrize.h"
#include "schemes/geometry-image/creation/triangle_mesh.h"
#include "schemes/geometry-image/image.h"

namespace sdb::gim {

// Bumped whenever a change to creation changes its results, so that old cache files are not used.
// 2: fitted to the input's Catmull-Clark limit surface (1 fitted the flat control polygons).
inline constexpr int kCreationVersion = 2;

struct CreationOptions {
  int size = 65;  // n: samples per image side, odd, >= 5
  FitOptions fit;
  SphericalParametrizationOptions parametrization;
  bool use_cache = true;
  std::string cache_dir;  // empty: ImageCache::default_directory()
};

struct CreationReport {
  bool from_cache = false;
  std::string cache_path;  // the file read or written ("" when not cached)
  std::string cache_refused;  // a cache file refused and refitted, and why ("" when none was)
  // Wall-clock milliseconds of each step of the creation that made the image (also when it came
  // from the cache: the figures stored with it). Parametrization is shared by every size made by
  // one GeometryImageCreator and counted for the first only.
  double parametrize_ms = 0, sample_ms = 0, fit_ms = 0;
  double stretch = 0;           // L2 stretch of the spherical parametrization
  int cg_iterations = 0;
  double rms_residual = 0;      // of the fit against the dense samples, in model units
  int unknowns = 0;
  long samples = 0;
};

struct CreatedImage {
  GeometryImage image;
  CreationReport report;
};

// Creates images of any size from one mesh, parametrizing it once.
class GeometryImageCreator {
 public:
  // Throws InputError unless the mesh is closed, manifold, genus 0 and connected.
  explicit GeometryImageCreator(const ControlMesh& mesh, CreationOptions options = {});
  ~GeometryImageCreator();

  CreatedImage create(int size);
  // The parametrization (computed on first use).
  const SphericalParametrization& parametrization();
  const TriangleMesh& surface() const { return surface_; }
  // The input's Catmull-Clark limit surface, what the image is fitted to, and its closest points
  // (built on first use).
  const LimitEvaluator& limit();
  const LimitProjector& projector();
  // The cache key of an image of this mesh (content and creation settings).
  uint64_t cache_key() const;

 private:
  ControlMesh mesh_;
  CreationOptions options_;
  TriangleMesh surface_;
  FaceDomains domains_;  // of surface_'s triangles
  std::optional<SphericalParametrization> parametrization_;
  std::unique_ptr<LimitEvaluator> limit_;
  std::unique_ptr<LimitProjector> projector_;
  double parametrize_ms_ = 0;
  bool parametrize_reported_ = false;
};

CreatedImage create_geometry_image(const ControlMesh& mesh, const CreationOptions& options = {});

// The dense samples of the limit surface, through `parametrization` and the octahedral map, on the
// grid the fit of an n x n image uses. `domains` are those of the triangles of the mesh the
// parametrization was computed from (it refines them as the parametrization refined its surface).
DenseSamples sample_limit_surface(const SphericalParametrization& parametrization, const FaceDomains& domains,
                                  const LimitEvaluator& limit, int n);

}  // namespace sdb::gim
