// Rows measured in a worker process, so that a crash in third-party code (OpenSubdiv, Embree,
// OpenMesh, a Vulkan driver) ends one row, as a "failed" row with the signal named, and the run
// goes on in a new worker.
//
// The worker is this executable started afresh (posix_spawn of /proc/self/exe, the hidden verb
// `row-worker`), not a fork: by the time `run` measures it has TBB's workers, a Vulkan device and
// llvmpipe's threads, and a forked copy of a threaded process may wait forever on their locks.
// One worker serves rows until one kills it, keeping the meshes and reference surfaces it built
// (MeasureContext) as a run in one process does: a worker per row measured the same figures but
// paid 0.2 s of dynamic linking (266 libraries) and the reference surfaces again for every row
// (harness/bench/README.md has the figures). Jobs and reports travel as JSON lines on a socket
// pair (the worker's descriptor 3): each job, then the stage the worker enters ("prepare",
// "execute", "validate", "time") with the row as it stands, then the row or the error.
#pragma once

#include <memory>
#include <string>

#include "harness/bench/measure.h"

namespace sdb {

class ChannelProcess;

// The options as a job carries them to the worker (one JSON line), and back: every field that
// shapes a row (on_stage, a function, stays with the process that set it).
std::string options_line(const MeasureOptions& options);
MeasureOptions options_from_line(const std::string& line);

class RowWorker {
 public:
  // `executable`: the binary to start (this one: its schemes are the ones planned).
  RowWorker(std::string executable, MachineInfo machine, MeasureOptions options);
  ~RowWorker();

  // measure_run in the worker: the same row, or the same InputError / Unsupported / internal
  // error. A worker that dies gives a "failed" row naming the signal and the stage, and the next
  // row starts a new one. A worker killed by SIGINT, SIGTERM or SIGHUP (Ctrl-C reaches the whole
  // process group) ends this process by the same signal, with no row: the run was interrupted,
  // not the row's code broken.
  RunRow measure(const RunSpec& spec);

 private:
  std::string executable_;
  MachineInfo machine_;
  MeasureOptions options_;
  std::unique_ptr<ChannelProcess> process_;
};

// The worker's side (`subdivbench row-worker --channel-fd 3 --parent PID`): measures each job it
// reads on `channel_fd` and reports there, until the channel closes. Ends the process without
// running destructors, so that a library's teardown cannot turn measured rows into a crash.
[[noreturn]] void serve_rows(int channel_fd, long parent);

}  // namespace sdb
