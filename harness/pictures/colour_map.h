// The colour map of the deviation pictures: viridis (perceptually uniform, readable in grey and by
// the colour-blind), and the colour bar drawn with it. The range's numbers are the manifest's,
// written beside the bar by the report: the bar itself runs from 0 to 1.
#pragma once

#include <cstdint>

#include "harness/core/control_mesh.h"
#include "harness/gpu/image.h"

namespace sdb::pictures {

// RGB in [0, 1] at t in [0, 1] (clamped; NaN gives the low end).
Point3 viridis(float t);

// Low end on the left, a one-pixel grey frame around it.
gpu::Image colour_bar(uint32_t width, uint32_t height);

}  // namespace sdb::pictures
