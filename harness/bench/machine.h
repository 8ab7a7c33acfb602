// The machine block of results.json, and the calibration probe every row is read against.
#pragma once

#include <optional>
#include <string>

#include "harness/results/results.h"

namespace sdb {

// CPU, memory, compiler, build type, git commit, and (probe_devices) the Vulkan device and the
// OpenGL context a run would use; the probes load the drivers, which costs llvmpipe its LLVM.
MachineInfo describe_machine(bool probe_devices = true);

// The first field, as far as it shapes rows, in which `now` differs from `journalled` ("CPU 'x',
// now 'y'"; the probes' bandwidths are measured, not compared); "" when none does.
std::string machine_difference(const MachineInfo& journalled, const MachineInfo& now);

// Now, ISO 8601 in UTC (results' `created`).
std::string utc_now();

// Achievable write bandwidth in GB/s: sequential stores over a buffer several times the last-level
// cache, best of five passes, on one thread and on `threads` TBB workers (the same buffer).
struct CpuWriteBandwidth {
  double one_thread_gbs = 0;
  double all_threads_gbs = 0;
};
CpuWriteBandwidth measure_write_bandwidth(int threads);

// The write-bandwidth probes (about a second: the buffer filled five times per thread count, and
// the GPU's 256 MiB where there is one) added to a description.
void add_bandwidth_probes(MachineInfo& m);
// describe_machine() with the write-bandwidth probes measured (CPU one thread, all threads, and
// the Vulkan device when there is one): what every results file records.
MachineInfo describe_machine_with_probes();

// bench --machine-from FILE and the reused probes below: the machine block of a results file
// written here, probes included, its probes_from naming the file. InputError where it describes
// another machine or build than this one (machine_difference, the commit); with devices_probed
// false the devices are not probed here (the reuse's key vouches for them).
MachineInfo machine_from(const std::string& path, bool devices_probed = true);

// Probes measured once per machine, boot and build, and reused by the processes that follow:
// where $SUBDIVBENCH_MACHINE_PROBES names a folder (ctest's environment sets it to one in the
// build folder), a run or bench process takes its machine block, probes included, from the file
// there named for this boot, this executable's build id and the environment that picks the Vulkan
// and OpenGL devices, which the first such process wrote (keep_machine_probes). Without the
// variable, or with no usable file, nullopt: the process probes as a user's does.
inline constexpr const char* kMachineProbesVariable = "SUBDIVBENCH_MACHINE_PROBES";
std::optional<MachineInfo> reused_machine_probes();
// describe_machine(), or the reused block where there is one.
MachineInfo describe_machine_or_reuse();
// Writes a block whose probes this process measured to that file (atomically: written beside it,
// then renamed), for the next process; nothing without the variable or when it was reused.
void keep_machine_probes(const MachineInfo& m);

// The same for the Vulkan device: a buffer fill timed by timestamp queries; 0 without a device.
double measure_gpu_write_bandwidth();
// What a compute shader writes there: 128 MiB of vec4s, 8 consecutive per invocation, nothing
// computed (harness/gpu/shaders/store_probe.comp), timed by timestamp queries; 0 without a
// device. On lavapipe a shader's stores go lane by lane, so this is a fraction of the fill's
// memset, and it bounds the bandwidth fraction any row can reach (harness/bench/README.md).
double measure_gpu_shader_write_bandwidth();

}  // namespace sdb
