// The deterministic gate: instructions executed by Evaluation::execute() under valgrind's
// callgrind, for the fixed workloads of ci/gate.json, against recorded counts. valgrind is
// spawned with an argument vector, never through a shell.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "harness/results/run_spec.h"

namespace sdb {

struct CallgrindConfig {
  std::vector<RunSpec> workloads;  // cpu rows only
  double threshold = 0.02;
};

// The "callgrind" section of a gate configuration; InputError for a malformed file or workload.
CallgrindConfig read_callgrind_config(const std::string& path);

// The child process (`subdivbench workload ...`) is measurement's: harness/bench/callgrind_workload.h.

// Why valgrind cannot run `executable` on this machine at all, or nullopt: valgrind stops (SIGILL)
// at an instruction it cannot decode that a library runs while loading (seen: libhwy's rdtscp,
// loaded with OpenImageIO, on a CPU whose CPUID does not announce rdtscp; OpenImageIO is now
// opened only where an image is read or written, harness/images/image_io.h). A limit of the tool on
// the machine, not of the workload: tests skip on it, the gate says it. Checked once per process.
std::optional<std::string> valgrind_unusable(const std::string& executable);

// Instructions of `iterations` executions of the workload, counted by a child
// `valgrind --tool=callgrind <executable> workload ...`. InputError when valgrind fails.
long callgrind_instructions(const RunSpec& spec, int iterations, const std::string& executable);

struct CallgrindEntry {
  std::string name;
  double baseline = 0, current = 0, change = 0;
  bool regression = false;
};

// Counts every workload; compares with `baseline` (name -> count) where it has the workload.
std::vector<CallgrindEntry> callgrind_compare(const CallgrindConfig& config, const std::map<std::string, long>& counts,
                                              const std::map<std::string, long>& baseline);

// Reads / writes a callgrind baseline (a JSON object of name -> count). InputError on failure.
std::map<std::string, long> read_callgrind_counts(const std::string& path);
void write_callgrind_counts(const std::map<std::string, long>& counts, const std::string& path);

}  // namespace sdb
