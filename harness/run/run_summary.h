// What `run` says when it ends: how many rows were ok, unsupported and failed, each row whose closed
// input came out with open edges or ray cracks, the failures' reasons, and where the files are.
#pragma once

#include <string>
#include <vector>

#include "harness/results/results.h"

namespace sdb {

struct RunSummary {
  size_t ok = 0, unsupported = 0, failed = 0;
  std::vector<std::string> not_watertight;  // "name: 2 open edges, 5 ray cracks of 100000 rays"
  std::vector<std::string> failures;        // "name: message", failures that are not a crack
};

RunSummary summarise(const std::vector<RunRow>& rows);

// Lines to print: the counts, the rows named, and the files written (`report_dir` empty: no report).
std::vector<std::string> summary_lines(const RunSummary& summary, const std::string& results_json,
                                       const std::string& report_dir);

// From the paired cells: for each mesh and backend, the fastest scheme (triangle rate from its
// paired median time, either side of a cell) and, where it has a peer, its paired ratio with the
// range over rounds; then each backend cell, a GPU row against its own scheme's cpu-mt row; no
// lines without cells. With `machine`, a backend that ran on a CPU implementation of its API
// (lavapipe, llvmpipe) is marked "vulkan*" and a last line says what it is.
std::vector<std::string> paired_lines(const std::vector<PairedCell>& cells, const MachineInfo* machine = nullptr);

// Whether a closed input's row shows an open edge or a ray crack (rows on open inputs have their
// boundary as open edges by design and no ray test).
bool has_crack(const RunRow& row);

}  // namespace sdb
