// Per-vertex deviation written as a PLY mesh (vertex properties `deviation_pct` and `normal_deg`)
// so that reports and viewers (MeshLab, our report script) can draw heat maps.
#pragma once

#include <string>

#include "harness/core/tessellation.h"
#include "harness/validate/deviation.h"

namespace sdb {

void write_deviation_ply(const Tessellation& t, const DeviationReport& d, const std::string& path);

}  // namespace sdb
