// The summary cells of a run measured in paired rounds: for each mesh and each scheme+backend, its
// row at the level nearest a million output triangles and its peer's row (SchemeInfo::peer, on
// the row's peer backend) at the level nearest in triangles, timed round by round in a fresh
// random order (bench_runs' rounds), so that both sides of each round's ratio saw the same
// machine. A ratio of two single-pass rows, measured minutes apart beside other work, is noise.
#pragma once

#include <string>
#include <vector>

#include "harness/bench/measure.h"
#include "harness/results/results.h"

namespace sdb {

class Progress;

// A cell to measure: two ok rows of the run, the scheme's and its peer's, on one mesh.
struct PairedPlanCell {
  RunRow row, peer;
};

// The cells of `rows` in row order: rows that are not ok, have no peer or whose peer has no ok
// row on the same mesh and backend give none. After them the backend cells: each GPU row chosen
// (vulkan, opengl) against its own scheme's cpu-mt row on the same mesh and level, where the run
// has one: how the device path of a method compares with its CPU path, measured in the same rounds.
std::vector<PairedPlanCell> choose_paired_cells(const std::vector<RunRow>& rows, long target = kSummaryTriangles);

// A backend cell (above): the peer side is the row's own scheme on the CPU (results.h has the
// results file's PairedCell's).
bool is_backend_cell(const PairedPlanCell& c);

// The cell from its two sides measured in the same `rounds` rounds: sample r of each in round r
// (GPU time for GPU backends, wall time otherwise, as the rows' rates).
PairedCell pair_rounds(const std::string& mesh, const RunRow& row, const RunRow& peer);

struct PairedOptions {
  int rounds = 5;
  double min_time_s = 0.05;  // per benchmark and round
};

// The cells of rows that were measured in the same rounds already (bench --rounds: sample r of
// every row is round r), paired from their samples, in choose_paired_cells' order.
std::vector<PairedCell> pair_measured_rows(const std::vector<RunRow>& rows, long target = kSummaryTriangles);

// Measures the cells mesh by mesh (each mesh's evaluations alive only while its rounds run). A mesh
// whose rounds fail is reported through `note` and left out, never ending the run.
std::vector<PairedCell> measure_paired(const std::vector<PairedPlanCell>& cells, const PairedOptions& options,
                                       MeasureContext& context, Progress* progress,
                                       const std::function<void(const std::string&)>& note);

// Items measure_paired shows progress for: a round of a mesh's cells is one.
size_t paired_items(const std::vector<PairedPlanCell>& cells, int rounds);

}  // namespace sdb
