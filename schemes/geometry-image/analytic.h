// Analytic geometry images: a sphere and an ellipsoid sampled straight through the octahedral
// map, with no fit, so that timings and the paper's Table 2 (a 31 x 31 image) do not depend on
// the creation pipeline. The cut vertices are then moved to the centroids of their neighbours
// (equation 2), as every geometry image this scheme subdivides has them, so the surface is C1.
//
// Manifest names: gim-sphere-<n> and gim-ellipsoid-<n> (n odd, >= 5), e.g. gim-sphere-31. The
// mesh they name is the image's closed control mesh g0 (closed_mesh.h), which the
// geometry-image scheme recognises as an image and every other scheme takes as a quad mesh.
#pragma once

#include <optional>
#include <string>

#include "harness/core/control_mesh.h"
#include "schemes/geometry-image/image.h"

namespace sdb::gim {

enum class AnalyticShape { Sphere, Ellipsoid };

// Radii of the ellipsoid: three distinct axes so that no symmetry of the shape hides a mistake.
inline constexpr double kEllipsoidRadii[3] = {1.2, 0.8, 0.6};

GeometryImage analytic_image(AnalyticShape shape, int n);

// "gim-sphere-31" -> g0 of that image; nullopt for names of another form. Throws InputError for
// a well-formed name with a size that cannot be a geometry image (even, or below 5).
std::optional<ControlMesh> analytic_mesh_from_name(const std::string& name);

}  // namespace sdb::gim
