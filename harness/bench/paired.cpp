#include "harness/bench/paired.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "harness/bench/progress.h"
#include "harness/core/backend.h"
#include "harness/results/statistics.h"

namespace sdb {
namespace {

bool usable(const RunRow& r) { return r.status == RunStatus::Ok && r.triangles > 0; }

// The peer's row for `row`: same mesh, the peer scheme on the row's peer backend, nearest in
// triangles; a row spelled without parameters before one with them.
const RunRow* peer_row(const RunRow& row, const std::vector<RunRow>& rows) {
  const RunRow* best = nullptr;
  auto better = [&](const RunRow& r) {
    if (!best) return true;
    const bool plain = r.spelled() == r.scheme, best_plain = best->spelled() == best->scheme;
    if (plain != best_plain) return plain;
    return log_distance(r.triangles, row.triangles) < log_distance(best->triangles, row.triangles);
  };
  for (const RunRow& r : rows)
    if (usable(r) && r.mesh == row.mesh && r.scheme == row.peer && r.backend == *row.peer_backend && better(r)) best = &r;
  return best;
}

const std::vector<double>& round_samples(const RunRow& r) {
  return r.gpu_time_ms ? r.gpu_time_ms->samples : r.time_ms.samples;
}

RunSpec spec_for(const RunRow& r) { return {r.spelled(), r.mesh, r.backend, r.level}; }

}  // namespace

std::vector<PairedPlanCell> choose_paired_cells(const std::vector<RunRow>& rows, long target) {
  // The row nearest the target of each mesh and scheme+backend, in the order first seen.
  std::vector<std::string> order;
  std::map<std::string, const RunRow*> nearest;
  for (const RunRow& r : rows) {
    if (!usable(r) || r.peer.empty() || !r.peer_backend) continue;
    const std::string key = r.mesh + "|" + r.spelled() + "|" + std::string(to_string(r.backend));
    auto [it, fresh] = nearest.emplace(key, &r);
    if (fresh) order.push_back(key);
    else if (log_distance(r.triangles, target) < log_distance(it->second->triangles, target)) it->second = &r;
  }
  std::vector<PairedPlanCell> cells;
  for (const std::string& key : order) {
    const RunRow& row = *nearest[key];
    if (const RunRow* peer = peer_row(row, rows)) cells.push_back({row, *peer});
  }
  for (const std::string& key : order) {
    const RunRow& row = *nearest[key];
    if (!is_gpu(row.backend)) continue;
    if (const RunRow* cpu = same_run_on(row, Backend::CpuMt, rows); cpu && usable(*cpu)) cells.push_back({row, *cpu});
  }
  return cells;
}

bool is_backend_cell(const PairedPlanCell& c) { return c.peer.spelled() == c.row.spelled() && c.peer.backend != c.row.backend; }

PairedCell pair_rounds(const std::string& mesh, const RunRow& row, const RunRow& peer) {
  PairedCell c;
  c.mesh = mesh;
  c.row = {row.spelled(), row.backend, row.level, row.triangles};
  c.peer = {peer.spelled(), peer.backend, peer.level, peer.triangles};
  const std::vector<double>& t = round_samples(row);
  const std::vector<double>& tp = round_samples(peer);
  c.rounds = static_cast<int>(std::min(t.size(), tp.size()));
  for (int r = 0; r < c.rounds; ++r)
    c.rate_ratio_per_round.push_back((double(row.triangles) / t[r]) / (double(peer.triangles) / tp[r]));
  if (c.rounds == 0) return c;
  const auto [lo, hi] = std::minmax_element(c.rate_ratio_per_round.begin(), c.rate_ratio_per_round.end());
  c.rate_ratio_min = *lo, c.rate_ratio_max = *hi;
  c.rate_ratio_median = median(c.rate_ratio_per_round);
  c.time_ms_median = median(std::vector<double>(t.begin(), t.begin() + c.rounds));
  c.peer_time_ms_median = median(std::vector<double>(tp.begin(), tp.begin() + c.rounds));
  return c;
}

std::vector<PairedCell> pair_measured_rows(const std::vector<RunRow>& rows, long target) {
  std::vector<PairedCell> out;
  for (const PairedPlanCell& c : choose_paired_cells(rows, target)) {
    PairedCell cell = pair_rounds(c.row.mesh, c.row, c.peer);
    if (cell.rounds > 0) out.push_back(std::move(cell));
  }
  return out;
}

namespace {

// Each mesh's distinct rows to time (a row can be one cell's scheme and another's peer).
std::map<std::string, std::vector<RunSpec>> specs_by_mesh(const std::vector<PairedPlanCell>& cells) {
  std::map<std::string, std::vector<RunSpec>> specs;
  std::map<std::string, std::set<std::string>> seen;
  for (const PairedPlanCell& c : cells)
    for (const RunRow* r : {&c.row, &c.peer})
      if (seen[r->mesh].insert(r->name()).second) specs[r->mesh].push_back(spec_for(*r));
  return specs;
}

}  // namespace

size_t paired_items(const std::vector<PairedPlanCell>& cells, int rounds) {
  return specs_by_mesh(cells).size() * size_t(std::max(rounds, 0));
}

std::vector<PairedCell> measure_paired(const std::vector<PairedPlanCell>& cells, const PairedOptions& options,
                                       MeasureContext& context, Progress* progress,
                                       const std::function<void(const std::string&)>& note) {
  std::map<std::string, RunRow> measured;  // by row name
  for (const auto& [mesh, specs] : specs_by_mesh(cells)) {
    MeasureOptions m;
    m.validate = false;
    m.refusals_as_rows = true;
    try {
      for (RunRow& r : bench_runs(specs, m, context, nullptr, {options.rounds, options.min_time_s, false, progress}))
        measured[r.name()] = std::move(r);
    } catch (const std::exception& e) {
      if (note) note("paired rounds on " + mesh + " left out: " + e.what());
    }
  }
  std::vector<PairedCell> out;
  for (const PairedPlanCell& c : cells) {
    const auto row = measured.find(c.row.name()), peer = measured.find(c.peer.name());
    if (row == measured.end() || peer == measured.end()) continue;
    PairedCell cell = pair_rounds(c.row.mesh, row->second, peer->second);
    if (cell.rounds > 0) out.push_back(std::move(cell));
  }
  return out;
}

}  // namespace sdb
