// The smooth geometry image scheme (Losasso, Hoppe, Schaefer, Warren 2003), CPU backends.
//
// Which image a run subdivides: a mesh whose connectivity is exactly the closed control mesh g0
// of an n x n geometry image (closed_mesh.h) is that image, used as is: the analytic manifest
// meshes gim-sphere-<n> / gim-ellipsoid-<n> (analytic.h), or any g0 written out before. Any
// other closed genus-0 mesh is turned into an image of GeometryImageOptions::fit_size by the
// creation pipeline (creation/create.h), cached on disk. See README.md.
#pragma once

#include <memory>

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

// The scheme "geometry-image" (backends cpu, cpu-mt).
std::unique_ptr<Scheme> make_geometry_image_scheme(const GeometryImageOptions& options = {});

}  // namespace sdb
