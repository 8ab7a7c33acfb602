// The smooth geometry image scheme (Losasso, Hoppe, Schaefer, Warren 2003): backends cpu,
// cpu-mt and vulkan, as two scheme names, one per pass plan (README.md).
//
// Which image a run subdivides: a mesh whose connectivity is exactly the closed control mesh g0
// of an n x n geometry image (closed_mesh.h) is that image, used as is: the analytic manifest
// meshes gim-sphere-<n> / gim-ellipsoid-<n> (analytic.h), or any g0 written out before. Any
// other closed genus-0 mesh is turned into an image of the request's `fit` parameter (samples a
// side, `--scheme geometry-image:fit=129`) by the creation pipeline (creation/create.h), cached on
// disk. See README.md.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "harness/core/scheme.h"
#include "schemes/geometry-image/subdivision.h"

namespace sdb {

inline constexpr int kDefaultFitSize = 65;

// The `fit` parameter: samples a side of images fitted to ordinary meshes, odd, 5..513; by
// default 2^6 + 1, which subsamples down to the octahedron.
ParameterSpec fit_size_parameter();

// "geometry-image" for PassPlan::Fused (L+A per level, E+T: the default), "geometry-image-permask"
// for PassPlan::PerMask (pad, L, A, E, T: one pass per mask, as the paper). Names are part of the
// results contract.
std::string geometry_image_scheme_name(gim::PassPlan plan);

// The scheme of `plan`, named as above (backends cpu, cpu-mt, vulkan).
std::unique_ptr<Scheme> make_geometry_image_scheme(gim::PassPlan plan = gim::PassPlan::Fused);

// geometry-image, geometry-image-permask.
std::vector<std::unique_ptr<Scheme>> make_geometry_image_schemes();

}  // namespace sdb
