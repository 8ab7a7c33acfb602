// The machine block of results.json, and the calibration probe every row is read against.
#pragma once

#include "results.h"

namespace sdb {

// CPU, memory, compiler, build type, git commit, and the Vulkan device a run would use.
MachineInfo describe_machine();

// Achievable write bandwidth in GB/s: sequential stores over a buffer several times the last-level
// cache, best of a few passes; `threads` > 1 splits the buffer across TBB workers.
double measure_write_bandwidth(int threads);

}  // namespace sdb
