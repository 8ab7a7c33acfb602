// Where the pictures of one mesh are seen from: one camera for every scheme's surface on it, so
// that side by side they differ only where the surfaces do.
#pragma once

#include <vector>

#include "harness/core/tessellation.h"
#include "harness/gpu/mesh_renderer.h"

namespace sdb::pictures {

// The view that shows most of the surface: of the renderer's default oblique view and views
// 25 degrees above the horizon every 30 degrees around (none along an axis, where a box shows
// one face), the one under which its triangles' projected area is largest. The default keeps its
// place unless another shows 5% more, so that round shapes are all seen alike.
Point3 view_direction(const Tessellation& surface);

// Looks from the first surface's view_direction and frames all of them (none null, at least one).
gpu::Camera picture_camera(const std::vector<const Tessellation*>& surfaces, float aspect);

}  // namespace sdb::pictures
