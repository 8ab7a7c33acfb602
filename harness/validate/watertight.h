// Watertightness: the exact weld check and the Embree ray-crack check (ARCHITECTURE.md,
// "Validation, defined").
#pragma once

#include <cstdint>

#include "harness/core/tessellation.h"

namespace sdb {

// ExactWeldCheck: welds vertices whose float32 positions are bit-identical and counts edges used
// by exactly one triangle. 0 for a closed surface.
long count_open_edges(const Tessellation& t);

struct RayCheckOptions {
  long random_lines = 100000;  // lines through the bounding sphere
  long border_lines = 0;       // lines aimed at base-face borders; 0 means as many as random_lines
  uint64_t seed = 1;
};

struct RayCrackReport {
  long rays = 0;    // full lines cast
  long cracks = 0;  // lines that crossed the surface an odd number of times
  uint64_t seed = 0;
};

// RayCrackCheck: on a closed surface every full line crosses an even number of times; a line that
// does not found a crack. Lines passing within float resolution of a triangle edge are undecidable
// and replaced by fresh ones, so the check resolves gaps wider than about 1e-5 of a triangle;
// narrower splits are the exact weld check's.
RayCrackReport ray_crack_check(const Tessellation& t, const RayCheckOptions& options = {});

}  // namespace sdb
