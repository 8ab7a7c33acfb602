// Per-vertex deviation written as a PLY mesh (vertex properties `deviation_pct` and `normal_deg`)
// so that reports and viewers (MeshLab, our report script) can draw heat maps.
#pragma once

#include <string>

#include "harness/core/tessellation.h"
#include "harness/mesh/placement.h"
#include "harness/validate/deviation.h"

namespace sdb {

// `placement`: where the run moved the mesh from (placement.h); positions are written back in
// the file's own coordinates.
void write_deviation_ply(const Tessellation& t, const DeviationReport& d, const std::string& path,
                         const Placement& placement = {});

}  // namespace sdb
