#include "harness/bench/callgrind_workload.h"

#include <valgrind/callgrind.h>

#include "harness/bench/machine.h"
#include "harness/bench/measure.h"
#include "harness/core/errors.h"
#include "harness/core/registry.h"

namespace sdb {

void run_callgrind_workload(const RunSpec& spec, int iterations) {
  MeasureContext ctx(MachineInfo{});
  const ResolvedScheme r = resolve_scheme(spec.scheme);
  const auto mesh = ctx.accepted(spec.mesh, *r.scheme);
  const RunRequest request{spec.backend, spec.level, 0, r.parameters};
  if (auto why = declined(*r.scheme, request)) throw InputError(spec.name(), *why);
  auto eval = r.scheme->prepare(*mesh, request);
  // Once before counting: a first execute() binds the libraries' functions it calls (lazy PLT
  // binding, whose symbol search grows with every library loaded: 3.3 M instructions of the
  // 7.4 M counted for osd-bfr on the torus before OpenImageIO left the executable's start) and
  // lavapipe compiles a pipeline at its first dispatch. The counts are the workload's own.
  execute_on(*eval, spec.backend);
  CALLGRIND_START_INSTRUMENTATION;  // count execute() only, not loading or prepare()
  for (int i = 0; i < iterations; ++i) execute_on(*eval, spec.backend);
  CALLGRIND_STOP_INSTRUMENTATION;
}

}  // namespace sdb
