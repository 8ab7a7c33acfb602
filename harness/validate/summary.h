// What the validation figures (deviation, Hausdorff, distance from a limit surface) share: which
// output vertices lie on the surface, and max, mean, RMS and 95th percentile of a sample, the one
// definition every figure is summarised by. Included by the module's sources only.
#pragma once

#include <vector>

#include "harness/core/tessellation.h"

namespace sdb {

// Vertices used by at least one triangle: unreferenced ones (inside holes) have no surface.
std::vector<char> referenced(const Tessellation& t);

struct Stats {
  double max = 0, mean = 0, rms = 0, p95 = 0;
};

// Zeros for an empty sample.
Stats stats_of(std::vector<double> v);

}  // namespace sdb
