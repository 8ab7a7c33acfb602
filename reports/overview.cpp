#include "reports/overview.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "harness/results/statistics.h"

namespace sdb {
namespace {

using json = nlohmann::json;

bool usable(const RunRow& r) { return r.status == RunStatus::Ok && r.triangles > 0; }

std::string cell_key(const std::string& spec, const std::string& mesh, Backend b) {
  return spec + "|" + mesh + "|" + std::string(to_string(b));
}

// A summary cell: its row and, where the run paired it against its peer, the paired figures.
struct SummaryCell {
  const RunRow* row = nullptr;
  const PairedCell* paired = nullptr;
};

// The summary cells in the rows' order: per (scheme, mesh, backend) the row at the paired level
// where the run paired the cell against its peer, else the ok row nearest kSummaryTriangles, else
// (none ok) the row nearest it, to show its status.
std::vector<SummaryCell> summary_cells(const ResultsFile& results) {
  std::map<std::string, const PairedCell*> paired;
  for (const PairedCell& c : results.paired)
    if (!is_backend_cell(c)) paired[cell_key(c.row.scheme, c.mesh, c.row.backend)] = &c;
  std::vector<std::string> order;
  std::map<std::string, std::vector<const RunRow*>> rows;
  for (const RunRow& r : results.runs) {
    if (r.role == "calibration" || r.scheme == kCalibrationScheme) continue;
    auto& cell = rows[cell_key(r.spelled(), r.mesh, r.backend)];
    if (cell.empty()) order.push_back(cell_key(r.spelled(), r.mesh, r.backend));
    cell.push_back(&r);
  }
  auto nearest = [](const std::vector<const RunRow*>& rs, bool ok_only) -> const RunRow* {
    const RunRow* best = nullptr;
    for (const RunRow* r : rs)
      if ((!ok_only || usable(*r)) &&
          (!best || log_distance(r->triangles, kSummaryTriangles) < log_distance(best->triangles, kSummaryTriangles)))
        best = r;
    return best;
  };
  std::vector<SummaryCell> out;
  for (const std::string& key : order) {
    const auto& rs = rows[key];
    const auto p = paired.find(key);
    if (p != paired.end()) {
      const auto at = std::find_if(rs.begin(), rs.end(), [&](const RunRow* r) { return r->level == p->second->row.level; });
      if (at != rs.end()) {
        out.push_back({*at, p->second});
        continue;
      }
    }
    const RunRow* ok = nearest(rs, true);
    out.push_back({ok ? ok : nearest(rs, false), nullptr});
  }
  return out;
}

double rate_of(const SummaryCell& c) {
  if (!usable(*c.row)) return 0;
  if (c.paired && c.paired->time_ms_median > 0 && c.paired->row.triangles > 0)
    return double(c.paired->row.triangles) / c.paired->time_ms_median / 1e3;
  return c.row->triangle_rate_mtris;
}

// Per row, its single-pass ratio to its peer's row (ReportOverview::row_peer_ratios).
std::vector<double> single_pass_ratios(const ResultsFile& results) {
  const auto key = [](const std::string& spec, const std::string& mesh, Backend b, int tessellation) {
    return cell_key(spec, mesh, b) + "|" + std::to_string(tessellation);
  };
  std::map<std::string, const RunRow*> ok_rows;  // the last ok row of each (spec, mesh, backend, tessellation)
  for (const RunRow& r : results.runs)
    if (r.status == RunStatus::Ok && r.scheme != kCalibrationScheme)
      ok_rows[key(r.spelled(), r.mesh, r.backend, r.tessellation)] = &r;
  std::vector<double> ratios;
  for (const RunRow& r : results.runs) {
    double ratio = NAN;
    if (r.status == RunStatus::Ok && !r.peer.empty() && r.peer_backend) {
      const auto peer = ok_rows.find(key(r.peer, r.mesh, *r.peer_backend, r.tessellation));
      if (peer != ok_rows.end() && peer->second->triangle_rate_mtris > 0 && std::isfinite(r.triangle_rate_mtris))
        ratio = r.triangle_rate_mtris / peer->second->triangle_rate_mtris;
    }
    ratios.push_back(ratio);
  }
  return ratios;
}

// The limit table: per (scheme, mesh), over its rows that recorded a claim and a deviation.
std::vector<LimitCell> limit_cells(const ResultsFile& results) {
  std::vector<std::string> order;
  std::map<std::string, std::vector<const RunRow*>> said;
  for (const RunRow& r : results.runs) {
    if (r.scheme == kCalibrationScheme || r.status == RunStatus::Unsupported) continue;
    if (r.limit != "reproduces" && r.limit != "approximates") continue;
    if (!r.deviation.measured && !(r.deviation.hausdorff_rel >= 0)) continue;  // no deviation recorded
    const std::string k = r.spelled() + "|" + r.mesh;
    auto& rows = said[k];
    if (rows.empty()) order.push_back(k);
    rows.push_back(&r);
  }
  const auto worst = [](double so_far, double x) { return std::isfinite(x) && !(x <= so_far) ? x : so_far; };
  std::vector<LimitCell> cells;
  for (const std::string& k : order) {
    const auto& rows = said[k];
    LimitCell c{rows.front()->spelled(), rows.front()->mesh};
    std::set<int> levels;
    for (const RunRow* r : rows) {
      if (r->limit != "approximates") continue;
      c.approximates = true;
      levels.insert(r->level);
      if (r->deviation.measured) {
        c.worst_max_rel_diag = worst(c.worst_max_rel_diag, r->deviation.pos_max_rel_diag);
        c.worst_p95_rel_diag = worst(c.worst_p95_rel_diag, r->deviation.pos_p95_rel_diag);
      }
      c.nearest_point |= r->deviation.measured_by == "nearest-point";
    }
    c.approximating_levels.assign(levels.begin(), levels.end());
    c.some_reproduce = std::any_of(rows.begin(), rows.end(), [](const RunRow* r) { return r->limit == "reproduces"; });
    cells.push_back(std::move(c));
  }
  return cells;
}

// Marks each point that no other point of the same backend dominates (as fast or faster and as
// near or nearer, strictly better in one).
void mark_pareto(std::vector<OverviewPoint>& points) {
  for (OverviewPoint& p : points) {
    p.pareto = std::none_of(points.begin(), points.end(), [&](const OverviewPoint& q) {
      return q.rate_mtris >= p.rate_mtris && q.plotted_p95 <= p.plotted_p95 &&
             (q.rate_mtris > p.rate_mtris || q.plotted_p95 < p.plotted_p95);
    });
  }
}

// Per mesh with a ray test (a closed input), whether every row of the scheme there is watertight.
void count_watertight(const ResultsFile& results, SchemeOverview& s) {
  std::map<std::string, bool> closed;  // mesh: watertight so far
  for (const RunRow& r : results.runs) {
    if (r.spelled() != s.scheme || r.status == RunStatus::Unsupported || r.watertight.ray_cracks < 0) continue;
    const bool tight = r.watertight.open_edges == 0 && r.watertight.ray_cracks == 0;
    auto [it, fresh] = closed.emplace(r.mesh, tight);
    if (!fresh) it->second = it->second && tight;
  }
  s.closed_inputs = int(closed.size());
  s.watertight_inputs = int(std::count_if(closed.begin(), closed.end(), [](const auto& m) { return m.second; }));
}

void add_paired_ratio(const ResultsFile& results, SchemeOverview& s) {
  std::vector<double> medians;
  for (const bool cpu_implementation_only : {false, true}) {
    for (const PairedCell& c : results.paired) {
      if (is_backend_cell(c) || c.row.scheme != s.scheme || c.rounds == 0) continue;
      if (on_cpu_implementation(results.machine, c.row.backend) != cpu_implementation_only) continue;
      if (medians.empty()) s.ratio_min = c.rate_ratio_min, s.ratio_max = c.rate_ratio_max;
      medians.push_back(c.rate_ratio_median);
      s.ratio_min = std::min(s.ratio_min, c.rate_ratio_min);
      s.ratio_max = std::max(s.ratio_max, c.rate_ratio_max);
    }
    if (!medians.empty()) break;  // a CPU implementation's cells only where the scheme has no other
  }
  s.paired_cells = int(medians.size());
  if (!medians.empty()) s.ratio_median = median(medians);
}

// Per mesh and backend, the fastest cell (the highest rate; on a tie the later spelling, as
// reports/report_summary.py chose it before) is marked.
std::vector<SummaryCellRef> summary_refs(const std::vector<SummaryCell>& cells, const ResultsFile& results,
                                         const std::vector<double>& row_peer_ratios) {
  std::vector<SummaryCellRef> refs;
  std::map<std::string, size_t> fastest;  // mesh|backend: index into refs
  for (const SummaryCell& c : cells) {
    const RunRow& r = *c.row;
    const double ratio = c.paired ? c.paired->rate_ratio_median : row_peer_ratios[size_t(c.row - results.runs.data())];
    refs.push_back({r.spelled(), r.mesh, r.backend, r.level, c.paired != nullptr, rate_of(c), false, ratio});
    const SummaryCellRef& mine = refs.back();
    if (!(mine.rate_mtris > 0)) continue;
    const std::string key = r.mesh + "|" + std::string(to_string(r.backend));
    const auto it = fastest.find(key);
    if (it == fastest.end()) fastest.emplace(key, refs.size() - 1);
    else if (std::make_pair(mine.rate_mtris, mine.scheme) > std::make_pair(refs[it->second].rate_mtris, refs[it->second].scheme))
      it->second = refs.size() - 1;
  }
  for (const auto& [key, i] : fastest) refs[i].fastest = true;
  return refs;
}

json number_or_null(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

}  // namespace

ReportOverview make_overview(const ResultsFile& results) {
  ReportOverview o;
  for (const RunRow& r : results.runs) o.row_bounds.push_back(judge_bounds(r));
  o.row_peer_ratios = single_pass_ratios(results);
  o.limits = limit_cells(results);
  std::map<Backend, BackendOverview> backends;
  std::map<std::string, SchemeOverview> schemes;
  std::vector<std::string> scheme_order;
  const std::vector<SummaryCell> cells = summary_cells(results);
  o.cells = summary_refs(cells, results, o.row_peer_ratios);
  for (const SummaryCell& c : cells) {
    if (!usable(*c.row)) continue;
    const RunRow& r = *c.row;
    BackendOverview& b = backends[r.backend];
    b.backend = r.backend;
    b.cpu_implementation = cpu_implementation_words(results.machine, r.backend);
    OverviewPoint p{r.spelled(), r.mesh, r.level, r.triangles, rate_of(c), c.paired != nullptr, r.limit == "reproduces",
                    r.deviation.measured ? r.deviation.pos_p95_rel_diag : NAN};
    auto [it, fresh] = schemes.emplace(p.scheme, SchemeOverview{p.scheme});
    if (fresh) scheme_order.push_back(p.scheme);
    SchemeOverview& s = it->second;
    if (s.peer.empty()) s.peer = r.peer;  // SchemeInfo::peer as the row recorded it; empty: the anchor
    // The best rate: among cells at the summary's size on a backend that is not a CPU implementation
    // of a GPU API, where the scheme has any such; a smaller cell's rate is mostly fixed costs.
    const bool in_band = r.triangles >= kSummaryLow && r.triangles <= kSummaryHigh;
    const auto rank = [](bool cpu_impl, bool band) { return (cpu_impl ? 0 : 2) + (band ? 1 : 0); };
    const int mine = rank(!b.cpu_implementation.empty(), in_band), best = rank(s.best_on_cpu_implementation, s.best_in_band);
    if (s.best_mesh.empty() || mine > best || (mine == best && p.rate_mtris > s.best_rate_mtris)) {
      s.best_rate_mtris = p.rate_mtris, s.best_backend = r.backend, s.best_mesh = r.mesh;
      s.best_on_cpu_implementation = !b.cpu_implementation.empty(), s.best_in_band = in_band;
    }
    if (r.limit == "approximates") {
      s.limit = "approximates";
      if (std::isfinite(p.p95_rel_diag)) s.worst_p95_rel_diag = std::max(s.worst_p95_rel_diag, p.p95_rel_diag);
    } else if (r.limit == "reproduces" && s.limit.empty()) {
      s.limit = "exact";
    }
    if (!in_band) {
      b.unplotted.push_back(p.scheme + " on " + p.mesh + ": " + std::to_string(p.triangles) +
                            " triangles, outside the summary's 0.5-2 M (its levels do not reach it there)");
      continue;
    }
    if (!p.exact && !std::isfinite(p.p95_rel_diag)) {
      b.unplotted.push_back(p.scheme + " on " + p.mesh + ": deviation not measured");
      continue;
    }
    p.plotted_p95 = p.exact ? kPrecisionFloorRelDiag : std::max(p.p95_rel_diag, kPrecisionFloorRelDiag);
    b.points.push_back(p);
  }
  for (auto& [backend, b] : backends) {
    mark_pareto(b.points);
    o.backends.push_back(std::move(b));
  }
  for (const std::string& name : scheme_order) {
    SchemeOverview& s = schemes[name];
    add_paired_ratio(results, s);
    count_watertight(results, s);
    o.schemes.push_back(s);
  }
  return o;
}

json overview_json(const ReportOverview& o) {
  json backends = json::array(), schemes = json::array();
  for (const BackendOverview& b : o.backends) {
    json points = json::array();
    for (const OverviewPoint& p : b.points)
      points.push_back({{"scheme", p.scheme}, {"mesh", p.mesh}, {"level", p.level}, {"triangles", p.triangles},
                        {"rate_mtris", p.rate_mtris}, {"paired", p.paired}, {"exact", p.exact},
                        {"p95_rel_diag", number_or_null(p.p95_rel_diag)}, {"plotted_p95", p.plotted_p95},
                        {"pareto", p.pareto}});
    backends.push_back({{"backend", to_string(b.backend)}, {"cpu_implementation", b.cpu_implementation},
                        {"points", points}, {"unplotted", b.unplotted}});
  }
  for (const SchemeOverview& s : o.schemes)
    schemes.push_back({{"scheme", s.scheme}, {"best_rate_mtris", s.best_rate_mtris},
                       {"best_backend", to_string(s.best_backend)}, {"best_mesh", s.best_mesh},
                       {"best_on_cpu_implementation", s.best_on_cpu_implementation}, {"best_in_band", s.best_in_band},
                       {"peer", s.peer},
                       {"paired_cells", s.paired_cells}, {"ratio_median", s.ratio_median}, {"ratio_min", s.ratio_min},
                       {"ratio_max", s.ratio_max}, {"limit", s.limit}, {"worst_p95_rel_diag", s.worst_p95_rel_diag},
                       {"closed_inputs", s.closed_inputs}, {"watertight_inputs", s.watertight_inputs}});
  json cells = json::array();
  for (const SummaryCellRef& c : o.cells)
    cells.push_back({{"scheme", c.scheme}, {"mesh", c.mesh}, {"backend", to_string(c.backend)}, {"level", c.level},
                     {"paired", c.paired}, {"rate_mtris", c.rate_mtris}, {"fastest", c.fastest},
                     {"ratio", number_or_null(c.ratio)}});
  json row_peer_ratios = json::array();
  for (const double ratio : o.row_peer_ratios) row_peer_ratios.push_back(number_or_null(ratio));
  json limits = json::array();
  for (const LimitCell& l : o.limits)
    limits.push_back({{"scheme", l.scheme}, {"mesh", l.mesh}, {"limit", l.approximates ? "approximates" : "reproduces"},
                      {"worst_max_rel_diag", number_or_null(l.worst_max_rel_diag)},
                      {"worst_p95_rel_diag", number_or_null(l.worst_p95_rel_diag)},
                      {"approximating_levels", l.approximating_levels}, {"some_reproduce", l.some_reproduce},
                      {"nearest_point", l.nearest_point}});
  json row_bounds = json::array();
  for (const BoundJudgement& j : o.row_bounds) row_bounds.push_back({to_string(j.state), j.words});
  return {{"precision_floor_rel_diag", kPrecisionFloorRelDiag}, {"summary_triangles", kSummaryTriangles},
          {"summary_band", {kSummaryLow, kSummaryHigh}},
          {"backends", backends}, {"schemes", schemes}, {"cells", cells}, {"row_bounds", row_bounds},
          {"row_peer_ratios", row_peer_ratios}, {"limits", limits}};
}

}  // namespace sdb
