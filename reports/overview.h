// The report's first screen as data: per backend, each scheme's summary cell on each mesh as a
// point (triangle rate against deviation from the input's limit surface) with the Pareto front
// marked, and one row per scheme (best rate, paired ratio to its peer, exact or approximates,
// watertight on every closed input). Computed here, once, in C++; reports/report.py lays it out.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "harness/results/bound_judgement.h"
#include "harness/results/results.h"

namespace sdb {

// Where the figure draws a row that reproduces the limit (and any whose p95 lies below it): the
// deviation of an exact evaluation in float is rounding, a few 1e-7 of the diagonal, and a log axis
// would otherwise rank rounding noise.
inline constexpr double kPrecisionFloorRelDiag = 1e-6;

struct OverviewPoint {
  std::string scheme, mesh;  // the spec, as rows spell it
  int level = 0;
  long triangles = 0;
  double rate_mtris = 0;  // the paired rounds' median where the run paired the cell, else the row's
  bool paired = false;
  bool exact = false;      // the row reproduces the input's limit surface (RunRow::limit)
  double p95_rel_diag = 0;  // measured p95 distance from the input's limit / diagonal; NaN: not measured
  double plotted_p95 = 0;   // p95_rel_diag, or kPrecisionFloorRelDiag for exact rows and those below it
  bool pareto = false;      // no other point of the backend is as fast and as near, and better in one
};

struct BackendOverview {
  Backend backend = Backend::Cpu;
  std::string cpu_implementation;  // "llvmpipe ..., a CPU implementation of Vulkan, not a GPU", or ""
  // Ok summary cells at the summary's size (plan.h: kSummaryLow..kSummaryHigh triangles) whose
  // deviation was measured or that reproduce the limit.
  std::vector<OverviewPoint> points;
  std::vector<std::string> unplotted;  // "scheme on mesh: why" for the other ok cells
};

struct SchemeOverview {
  std::string scheme;
  // The fastest summary cell on a backend that is not a CPU implementation of a GPU API (on one
  // only where the scheme has no other).
  double best_rate_mtris = 0;
  Backend best_backend = Backend::Cpu;
  std::string best_mesh;
  bool best_on_cpu_implementation = false;
  bool best_in_band = false;  // at kSummaryLow..kSummaryHigh triangles (plan.h); else the scheme has no such cell
  // Over its paired summary cells against its peer (not the backend cells): the median of their
  // medians, and the smallest and largest round.
  std::string peer;  // SchemeInfo::peer as its rows recorded it; empty: the anchor
  int paired_cells = 0;
  double ratio_median = 0, ratio_min = 0, ratio_max = 0;
  std::string limit;  // "exact" | "approximates" | "" (no row said)
  double worst_p95_rel_diag = 0;  // approximates: the largest p95 of its approximating cells
  int closed_inputs = 0, watertight_inputs = 0;  // meshes with a ray test, and those without an open edge or crack
};

// A summary cell as the report shows it: the row of (scheme, mesh, backend) at `level` (the paired
// level where the run paired the cell against its peer, else the ok row nearest kSummaryTriangles,
// else the nearest row, to show its status), its rate, and whether it is the fastest on its mesh
// and backend.
struct SummaryCellRef {
  std::string scheme, mesh;
  Backend backend = Backend::Cpu;
  int level = 0;
  bool paired = false;
  double rate_mtris = 0;  // as OverviewPoint's; 0 where the row is not ok
  bool fastest = false;
  // Its ratio to its peer: the paired rounds' median where the run paired the cell, else the row's
  // single-pass ratio (ReportOverview::row_peer_ratios); NaN where it has none.
  double ratio = NAN;
};

// What a scheme's rows on one mesh say of the input's limit surface (the report's limit table):
// every row that recorded a claim and a deviation reproduces it, or some approximate it, and then
// how closely at worst.
struct LimitCell {
  std::string scheme, mesh;
  bool approximates = false;
  // Over the approximating rows: the largest max and p95 distance / diagonal; NaN where none measured it.
  double worst_max_rel_diag = NAN, worst_p95_rel_diag = NAN;
  std::vector<int> approximating_levels;  // sorted, distinct
  bool some_reproduce = false;            // only some rows approximate (the others reproduce)
  bool nearest_point = false;             // an approximating row was measured by nearest points
};

struct ReportOverview {
  std::vector<SummaryCellRef> cells;  // every (scheme, mesh, backend) with a row, in the rows' order
  std::vector<BackendOverview> backends;
  // Per row of the results file, in its order: its deviation against its bounds (bound_judgement.h),
  // the words the summary and the validation grid print.
  std::vector<BoundJudgement> row_bounds;
  // Per row of the results file, in its order: its triangle rate over that of its peer's ok row
  // (RunRow::peer on RunRow::peer_backend, same mesh and tessellation) measured in the same pass;
  // NaN where the row is not ok or that row is missing or has no rate.
  std::vector<double> row_peer_ratios;
  // Per (scheme, mesh) with a row that said, in the order of the first row of each (calibration and
  // unsupported rows left out).
  std::vector<LimitCell> limits;
  std::vector<SchemeOverview> schemes;  // in the rows' order of first appearance
};

// The summary cells (SummaryCellRef) and, from their ok rows, the figures and the per-scheme table;
// each row's bound judgement and single-pass peer ratio; the limit table.
ReportOverview make_overview(const ResultsFile& results);

nlohmann::json overview_json(const ReportOverview& overview);

}  // namespace sdb
