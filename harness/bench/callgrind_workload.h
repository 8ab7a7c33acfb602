// The workload the instruction gate counts (harness/gate/callgrind.h), as the child process runs
// it: `subdivbench workload ...` under valgrind --tool=callgrind.
#pragma once

#include "harness/results/run_spec.h"

namespace sdb {

// Prepare untimed, then `iterations` executions between callgrind's instrumentation start and
// stop. InputError for a bad spec.
void run_callgrind_workload(const RunSpec& spec, int iterations);

}  // namespace sdb
