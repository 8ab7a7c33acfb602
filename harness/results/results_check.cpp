#include "harness/results/results_check.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "harness/core/errors.h"

namespace sdb {
namespace {

std::string number(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

// A figure that may be NaN (not measured) but, measured, is never below zero.
std::string negative(const char* what, double x) { return x < 0 ? std::string(what) + " is negative (" + number(x) + ")" : ""; }
std::string negative(const char* what, long x) { return x < 0 ? std::string(what) + " is negative (" + std::to_string(x) + ")" : ""; }

// Written from the same samples, the median lies inside [min, max]; the tolerance only absorbs a
// writer that rounded (JSON's doubles round-trip exactly).
bool inside(double x, double lo, double hi) {
  if (std::isnan(x) || std::isnan(lo) || std::isnan(hi)) return true;
  const double slack = 1e-9 * std::max({std::abs(lo), std::abs(hi), 1e-300});
  return lo <= x + slack && x <= hi + slack;
}

std::string range_words(const char* what, double median, double lo, double hi) {
  if (inside(median, lo, hi) && inside(lo, lo, hi)) return "";
  return std::string(what) + ": median " + number(median) + " outside its own range " + number(lo) + ".." + number(hi);
}

std::string impossible_time(const char* what, const TimeStats& t) {
  const std::string w = what;
  for (const auto& [name, x] : {std::pair{"median", t.median}, {"min", t.min}, {"max", t.max}})
    if (x < 0) return w + "." + name + " is a negative time (" + number(x) + ")";
  if (t.reps < 0) return w + ".reps is negative (" + std::to_string(t.reps) + ")";
  for (double s : t.samples)
    if (s < 0) return w + ": a negative sample (" + number(s) + ")";
  return range_words(what, t.median, t.min, t.max);
}

// The first non-empty reason of a list.
template <class... Reasons>
std::string first(const Reasons&... reasons) {
  for (const std::string* r : {&reasons...})
    if (!r->empty()) return *r;
  return "";
}

std::string impossible_watertight(const WatertightFigures& w) {
  if (w.open_edges < -1) return "watertight.open_edges is " + std::to_string(w.open_edges) + " (-1: not checked; else a count)";
  if (w.ray_cracks < -1) return "watertight.ray_cracks is " + std::to_string(w.ray_cracks) + " (-1: not checked; else a count)";
  if (w.rays < 0) return negative("watertight.rays", w.rays);
  if (w.ray_cracks > w.rays)
    return "watertight: " + std::to_string(w.ray_cracks) + " cracked rays of " + std::to_string(w.rays) + " cast";
  return "";
}

std::string impossible_deviation(const DeviationFigures& d) {
  if (d.hausdorff_rel < 0 && d.hausdorff_rel != -1) return "deviation.hausdorff_rel is " + number(d.hausdorff_rel) + " (-1: not measured)";
  if (!d.measured) return "";
  const std::pair<const char*, double> figures[] = {
      {"deviation.pos_max_pct", d.pos_max_pct},   {"deviation.pos_mean_pct", d.pos_mean_pct},
      {"deviation.pos_rms_pct", d.pos_rms_pct},   {"deviation.pos_p95_pct", d.pos_p95_pct},
      {"deviation.pos_max_rel_diag", d.pos_max_rel_diag}, {"deviation.normal_max_deg", d.normal_max_deg},
      {"deviation.normal_mean_deg", d.normal_mean_deg}};
  for (const auto& [what, x] : figures)
    if (x < 0) return negative(what, x);
  for (const auto& [what, x] : {std::pair{"deviation.pos_mean_pct", d.pos_mean_pct}, {"deviation.pos_rms_pct", d.pos_rms_pct},
                                {"deviation.pos_p95_pct", d.pos_p95_pct}})
    if (!inside(x, 0, d.pos_max_pct)) return std::string(what) + " " + number(x) + " is past pos_max_pct " + number(d.pos_max_pct);
  if (!inside(d.normal_mean_deg, 0, d.normal_max_deg))
    return "deviation.normal_mean_deg " + number(d.normal_mean_deg) + " is past normal_max_deg " + number(d.normal_max_deg);
  return "";
}

std::string impossible_counts(const RunRow& r) {
  return first(negative("triangles", r.triangles), negative("vertices", r.vertices), negative("bytes_out", r.bytes_out),
               negative("mesh_faces", long(r.mesh_faces)), negative("mesh_vertices", long(r.mesh_vertices)),
               r.tessellation < -1 ? "tessellation is " + std::to_string(r.tessellation) + " (segments per edge; -1: none)"
                                   : std::string());
}

std::string impossible_rates(const RunRow& r) {
  if (r.triangles == 0 && r.triangle_rate_mtris > 0)
    return "a triangle rate of " + number(r.triangle_rate_mtris) + " M/s at 0 triangles";
  std::string gpu;
  for (const GpuPassTime& p : r.gpu_passes)
    if (gpu.empty() && p.ms < 0) gpu = "gpu_passes: pass '" + p.label + "' took a negative time (" + number(p.ms) + ")";
  return first(negative("triangle_rate_mtris", r.triangle_rate_mtris), negative("bandwidth_fraction", r.bandwidth_fraction),
               negative("upload_ms", r.upload_ms), negative("readback_ms", r.readback_ms), gpu,
               inside(r.extraordinary_fraction, 0, 1) ? std::string()
                                                      : "extraordinary_fraction " + number(r.extraordinary_fraction) +
                                                            " is not a fraction");
}

std::string impossible_machine(const MachineInfo& m) {
  return first(negative("machine.cores", long(m.cores)), negative("machine.memory_gib", m.memory_gib),
               negative("machine.write_bandwidth_gbs", m.write_bandwidth_gbs),
               negative("machine.write_bandwidth_mt_gbs", m.write_bandwidth_mt_gbs),
               negative("machine.gpu_write_bandwidth_gbs", m.gpu_write_bandwidth_gbs),
               negative("machine.gpu_shader_write_bandwidth_gbs", m.gpu_shader_write_bandwidth_gbs));
}

}  // namespace

std::string impossible_row(const RunRow& r) {
  const std::string gpu = r.gpu_time_ms ? impossible_time("gpu_time_ms", *r.gpu_time_ms) : "";
  return first(impossible_time("time_ms", r.time_ms), gpu, impossible_counts(r), impossible_rates(r),
               impossible_watertight(r.watertight), impossible_deviation(r.deviation));
}

std::string impossible_paired_cell(const PairedCell& c) {
  if (c.rounds < 0) return "rounds is negative (" + std::to_string(c.rounds) + ")";
  if (!c.rate_ratio_per_round.empty() && c.rate_ratio_per_round.size() != size_t(c.rounds))
    return std::to_string(c.rate_ratio_per_round.size()) + " per-round ratios for " + std::to_string(c.rounds) + " rounds";
  for (double x : c.rate_ratio_per_round)
    if (x <= 0) return "a round's rate ratio is " + number(x) + " (a ratio of two rates is positive)";
  for (const auto& [what, x] : {std::pair{"rate_ratio.median", c.rate_ratio_median}, {"rate_ratio.min", c.rate_ratio_min},
                                {"rate_ratio.max", c.rate_ratio_max}})
    if (x <= 0) return std::string(what) + " is " + number(x) + " (a ratio of two rates is positive)";
  return first(range_words("rate_ratio", c.rate_ratio_median, c.rate_ratio_min, c.rate_ratio_max),
               negative("time_ms.median", c.time_ms_median), negative("peer_time_ms.median", c.peer_time_ms_median),
               negative("triangles", c.row.triangles), negative("peer.triangles", c.peer.triangles));
}

void check_results(const ResultsFile& results, const std::string& path, bool has_machine) {
  if (!has_machine) throw InputError(path, "no 'machine' section: figures that say not where they were measured");
  if (const std::string why = impossible_machine(results.machine); !why.empty()) throw InputError(path, why);
  if (results.rounds < 0) throw InputError(path, "'rounds' is negative (" + std::to_string(results.rounds) + ")");
  std::map<std::string, size_t> seen;
  for (size_t i = 0; i < results.runs.size(); ++i) {
    const std::string name = results.runs[i].name(), at = "runs[" + std::to_string(i) + "] " + name + ": ";
    if (const std::string why = impossible_row(results.runs[i]); !why.empty()) throw InputError(path, at + why);
    // A run is one row: two would be read as one by every reader, whichever it met first.
    if (const auto [it, fresh] = seen.emplace(name, i); !fresh)
      throw InputError(path, at + "the run's second row (the first is runs[" + std::to_string(it->second) + "])");
  }
  for (size_t i = 0; i < results.paired.size(); ++i)
    if (const std::string why = impossible_paired_cell(results.paired[i]); !why.empty()) {
      const PairedCell& c = results.paired[i];
      throw InputError(path, "paired[" + std::to_string(i) + "] " + c.row.scheme + "/" + std::string(to_string(c.row.backend)) +
                                 "/" + c.mesh + "/" + std::to_string(c.row.level) + ": " + why);
    }
}

}  // namespace sdb
