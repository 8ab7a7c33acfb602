#include "harness/gate/gate.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>

#include "harness/core/errors.h"
#include "harness/gate/mann_whitney.h"
#include "harness/results/statistics.h"

namespace sdb {
namespace {

const TimeStats& timing(const RunRow& r) { return r.gpu_time_ms ? *r.gpu_time_ms : r.time_ms; }

// Sample r of `t` over sample r of `unit` (same round) when the run went in rounds, else over the
// unit's fastest sample: interference only adds time, so the minimum is its stablest estimate.
std::vector<double> divided(const std::vector<double>& t, const std::vector<double>& unit, bool paired) {
  std::vector<double> out;
  if (paired && unit.size() == t.size()) {
    for (size_t i = 0; i < t.size(); ++i) out.push_back(t[i] / unit[i]);
  } else {
    const double m = *std::min_element(unit.begin(), unit.end());
    for (double s : t) out.push_back(s / m);
  }
  return out;
}

// The row's peer (RunRow::peer, from the scheme's SchemeInfo) at the same mesh and tessellation on
// the row's peer backend; else the calibration probe of the row's backend.
const RunRow* find_unit(const RunRow& row, const ResultsFile& file) {
  if (!row.peer.empty() && row.peer_backend)
    for (const RunRow& peer : file.runs)
      if (peer.scheme == row.peer && peer.status == RunStatus::Ok && peer.mesh == row.mesh &&
          peer.tessellation == row.tessellation && peer.backend == *row.peer_backend && !timing(peer).samples.empty())
        return &peer;
  for (const RunRow& probe : file.runs)
    if (probe.scheme == kCalibrationScheme && probe.backend == row.backend && !timing(probe).samples.empty()) return &probe;
  return nullptr;
}

// The same scheme, mesh and level on `backend`, where `config` names a backend for the row.
std::optional<Backend> own_normaliser(const RunRow& row, const GateConfig& config) {
  for (const auto& [pattern, backend] : config.normalisers)
    if (std::regex_search(row.name(), std::regex(pattern))) return backend;
  return std::nullopt;
}

}  // namespace

// Each repetition's time in units of the same run's peer time on the same mesh and tessellation;
// rows without a peer (the anchor, osd-bfr) in units of the calibration probe run beside them
// (bench --rounds), or failing that of the machine's bandwidth probe. When the run went in
// rounds, sample r is divided by the unit's sample r, measured moments apart, which cancels a
// busy machine's drift.
std::optional<NormalisedTimes> normalised_times(const RunRow& row, const ResultsFile& file, const GateConfig& config) {
  const TimeStats& t = timing(row);
  const bool paired = file.rounds > 0;
  if (const auto backend = own_normaliser(row, config)) {
    const RunRow* unit = same_run_on(row, *backend, file.runs);
    if (!unit || timing(*unit).samples.empty()) return std::nullopt;
    const std::string by = row.spec + "/" + std::string(to_string(*backend));
    return NormalisedTimes{divided(t.samples, timing(*unit).samples, paired), paired ? by + ", paired" : by};
  }
  if (const RunRow* unit = find_unit(row, file)) {
    const std::string by = unit->scheme == kCalibrationScheme ? "write probe" : unit->scheme;
    return NormalisedTimes{divided(t.samples, timing(*unit).samples, paired), paired ? by + ", paired" : by};
  }
  const double bw = row.backend == Backend::CpuMt    ? file.machine.write_bandwidth_mt_gbs
                    : is_gpu(row.backend)            ? file.machine.gpu_write_bandwidth_gbs
                                                     : file.machine.write_bandwidth_gbs;
  if (bw <= 0) return std::nullopt;
  NormalisedTimes n{{}, "bandwidth probe"};
  for (double s : t.samples) n.samples.push_back(s * bw);
  return n;
}

bool GateReport::failed() const {
  if (!problems.empty() || !gaps.empty()) return true;
  return other_machine.empty() &&
         std::any_of(entries.begin(), entries.end(), [](const GateEntry& e) { return e.regression; });
}

namespace {

// A significance level outside (0, 1) or a negative threshold would judge every change (or none)
// without saying so: found by tests/fuzz (alpha 1.01 was taken).
void require_judgeable(double alpha, double threshold, const std::string& path) {
  if (!(alpha > 0 && alpha < 1)) throw InputError(path, "alpha must lie between 0 and 1, not " + std::to_string(alpha));
  if (!(threshold >= 0) || !std::isfinite(threshold))
    throw InputError(path, "a threshold must be a relative change of 0 or more, not " + std::to_string(threshold));
}

// A whole number of 1 or more (a float such as 1e300 into an int is undefined behaviour).
int repetitions(const nlohmann::json& j, int fallback, const std::string& path) {
  if (!j.contains("min_repetitions")) return fallback;
  const nlohmann::json& v = j["min_repetitions"];
  if (!v.is_number_integer() || v < 1 || v > 1000000)
    throw InputError(path, "min_repetitions must be a whole number from 1 to 1000000, not " + v.dump());
  return v.get<int>();
}

// An entry's "match": a regular expression, or InputError naming the entry's kind.
std::string checked_pattern(const nlohmann::json& entry, const std::string& kind, const std::string& path) {
  const std::string pattern = entry.at("match").get<std::string>();
  try {
    (void)std::regex(pattern);
  } catch (const std::regex_error& e) {
    throw InputError(path, kind + " pattern '" + pattern + "' is not a regular expression: " + e.what());
  }
  return pattern;
}

}  // namespace

GateConfig read_gate_config(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, "is a directory, not a gate configuration");
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open gate configuration");
  GateConfig c;
  try {
    nlohmann::json j;
    in >> j;
    c.alpha = j.value("alpha", c.alpha);
    c.min_repetitions = repetitions(j, c.min_repetitions, path);
    c.default_threshold = j.value("default_threshold", c.default_threshold);
    require_judgeable(c.alpha, c.default_threshold, path);
    for (const auto& t : j.value("thresholds", nlohmann::json::array())) {
      const std::string pattern = checked_pattern(t, "threshold", path);
      c.thresholds.emplace_back(pattern, t.at("threshold").get<double>());
      require_judgeable(c.alpha, c.thresholds.back().second, path);
    }
    for (const auto& n : j.value("normalisers", nlohmann::json::array())) {
      const std::string pattern = checked_pattern(n, "normaliser", path), name = n.at("backend").get<std::string>();
      const auto backend = parse_backend(name);
      if (!backend) throw InputError(path, "normaliser backend '" + name + "' is not a backend");
      c.normalisers.emplace_back(pattern, *backend);
    }
    for (const auto& w : j.value("workload", nlohmann::json::array())) {
      try {
        c.workload.push_back(parse_run_name(w.get<std::string>()));
      } catch (const InputError& e) {
        throw InputError(path, std::string("workload: ") + e.what());
      }
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, std::string("malformed gate configuration: ") + e.what());
  }
  return c;
}

namespace {

bool same_machine(const MachineInfo& a, const MachineInfo& b) { return a.cpu_model == b.cpu_model && a.cores == b.cores; }

// Empty where both files name the same processor and core count (or either names none).
std::string other_machine(const MachineInfo& baseline, const MachineInfo& current) {
  if (baseline.cpu_model.empty() || current.cpu_model.empty() || same_machine(baseline, current)) return "";
  return "the baseline was recorded on " + baseline.cpu_model + " (" + std::to_string(baseline.cores) +
         " cores), this run is on " + current.cpu_model + " (" + std::to_string(current.cores) + " cores)";
}

}  // namespace

std::string machine_baseline_name(const MachineInfo& m) {
  std::string name;
  for (char c : m.cpu_model) {
    const bool keep = std::isalnum(static_cast<unsigned char>(c)) != 0;
    if (keep) name += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    else if (!name.empty() && name.back() != '-') name += '-';
  }
  if (!name.empty() && name.back() != '-') name += '-';
  return (name.empty() ? "unknown-" : name) + std::to_string(m.cores) + "c.json";
}

std::optional<std::string> baseline_for_machine(const MachineInfo& current, const std::vector<std::string>& files) {
  if (current.cpu_model.empty()) return std::nullopt;
  for (const std::string& f : files)
    if (same_machine(read_results(f).machine, current)) return f;
  return std::nullopt;
}

namespace {

// Every ok baseline benchmark must have an ok current row: those that have not are gaps; ok
// current rows the baseline lacks are new. Returns the pairs to judge, in the current file's order.
std::vector<std::pair<const RunRow*, const RunRow*>> pair_rows(const ResultsFile& baseline, const ResultsFile& current,
                                                               GateReport& report) {
  std::map<std::string, const RunRow*> base, now;
  for (const RunRow& r : baseline.runs)
    if (r.status == RunStatus::Ok && r.scheme != kCalibrationScheme) base.emplace(r.name(), &r);
  for (const RunRow& r : current.runs)
    if (r.scheme != kCalibrationScheme) now.emplace(r.name(), &r);
  for (const RunRow& r : baseline.runs) {
    if (r.status != RunStatus::Ok || r.scheme == kCalibrationScheme || base.at(r.name()) != &r) continue;
    const auto it = now.find(r.name());
    if (it == now.end()) report.gaps.push_back({r.name(), "missing from the current file (dropped or renamed)"});
    else if (it->second->status != RunStatus::Ok)
      report.gaps.push_back({r.name(), std::string(to_string(it->second->status)) + ": " + it->second->message});
  }
  std::vector<std::pair<const RunRow*, const RunRow*>> pairs;
  for (const RunRow& cur : current.runs) {
    if (cur.status != RunStatus::Ok || cur.scheme == kCalibrationScheme || now.at(cur.name()) != &cur) continue;
    const auto it = base.find(cur.name());
    if (it == base.end()) report.new_rows.push_back(cur.name());
    else pairs.emplace_back(it->second, &cur);
  }
  return pairs;
}

}  // namespace

GateReport run_gate(const ResultsFile& baseline, const ResultsFile& current, const GateConfig& config) {
  GateReport report;
  report.other_machine = other_machine(baseline.machine, current.machine);
  for (const auto& [old_row, cur_row] : pair_rows(baseline, current, report)) {
    const RunRow &old = *old_row, &cur = *cur_row;
    GateEntry e;
    e.name = cur.name();
    const int reps = std::min(timing(cur).reps, timing(old).reps);
    if (reps < config.min_repetitions || timing(cur).samples.size() < size_t(config.min_repetitions) ||
        timing(old).samples.size() < size_t(config.min_repetitions)) {
      report.problems.push_back(e.name + ": " + std::to_string(reps) + " repetitions, the gate needs " +
                                std::to_string(config.min_repetitions));
      continue;
    }
    const auto a = normalised_times(old, baseline, config), b = normalised_times(cur, current, config);
    if (!a || !b || a->by != b->by) {
      const auto own = own_normaliser(cur, config);
      report.problems.push_back(e.name + ": no common normaliser (" +
                                (own ? "its own row on " + std::string(to_string(*own))
                                     : "its peer " + (cur.peer.empty() ? std::string("(none)") : cur.peer) +
                                           ", the write probe or the bandwidth probe") +
                                ") in both runs");
      continue;
    }
    // A zero or missing time makes 0/0: NaN, which the rank test cannot order (it hung on it).
    auto finite = [](const std::vector<double>& v) {
      return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x) && x > 0; });
    };
    if (!finite(a->samples) || !finite(b->samples)) {
      report.problems.push_back(e.name + ": a time or its normaliser is zero or not a number");
      continue;
    }
    e.normaliser = b->by;
    e.change = median(b->samples) / median(a->samples) - 1;
    e.p_value = mann_whitney_p(a->samples, b->samples);
    e.threshold = config.default_threshold;
    for (const auto& [pattern, threshold] : config.thresholds)
      if (std::regex_search(e.name, std::regex(pattern))) {
        e.threshold = threshold;
        break;
      }
    const bool significant = e.p_value < config.alpha;
    e.regression = significant && e.change > e.threshold;
    e.improvement = significant && e.change < -e.threshold;
    report.entries.push_back(e);
  }
  return report;
}

}  // namespace sdb
