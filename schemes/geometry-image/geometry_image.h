// The smooth geometry image scheme (Losasso, Hoppe, Schaefer, Warren 2003): backends cpu,
// cpu-mt and vulkan, as two scheme names, one per pass plan (README.md).
//
// Which image a run subdivides: a mesh whose connectivity is exactly the closed control mesh g0
// of an n x n geometry image (closed_mesh.h) is that image, used as is: the analytic manifest
// meshes gim-sphere-<n> / gim-ellipsoid-<n> (analytic.h), or any g0 written out before. Any
// other closed genus-0 mesh is turned into an image of GeometryImageOptions::fit_size by the
// creation pipeline (creation/create.h), cached on disk. See README.md.
#pragma once

#include <memory>
#include <string>

#include "scheme.h"
#include "subdivision.h"

namespace sdb {

inline constexpr int kDefaultFitSize = 65;

struct GeometryImageOptions {
  // Samples a side of images fitted to ordinary meshes. 0: $SUBDIVBENCH_GIM_SIZE when set (an odd
  // number, 5..1025), else kDefaultFitSize, 2^6 + 1, which subsamples down to the octahedron.
  int fit_size = 0;
  gim::PassPlan plan = gim::PassPlan::Fused;
};

// fit_size resolved as above; throws InputError for a malformed $SUBDIVBENCH_GIM_SIZE.
int resolved_fit_size(const GeometryImageOptions& options);

// "geometry-image" for PassPlan::Fused (L+A per level, E+T: the default), "geometry-image-permask"
// for PassPlan::PerMask (pad, L, A, E, T: one pass per mask, as the paper). Names are part of the
// results contract.
std::string geometry_image_scheme_name(gim::PassPlan plan);

// The scheme of options.plan, named as above (backends cpu, cpu-mt, vulkan).
std::unique_ptr<Scheme> make_geometry_image_scheme(const GeometryImageOptions& options = {});

}  // namespace sdb
