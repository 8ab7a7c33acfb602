#include "gate.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <map>
#include <optional>
#include <regex>

#include "errors.h"
#include "mann_whitney.h"

namespace sdb {
namespace {

std::string name_of(const RunRow& r) { return r.scheme + "/" + r.backend + "/" + r.mesh + "/" + std::to_string(r.level); }

const TimeStats& timing(const RunRow& r) { return r.gpu_time_ms ? *r.gpu_time_ms : r.time_ms; }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : (v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]));
}

struct Normalised {
  std::vector<double> samples;
  std::string by;
};

// Each repetition's time in units of the same run's osd-bfr time on the same mesh, tessellation
// and backend; rows without such a peer (the peer itself) in units of the bandwidth probe.
// When the run went in rounds, sample r is divided by the peer's sample r, measured moments
// apart, which cancels a busy machine's drift. Otherwise the unit is the peer's fastest
// repetition: interference only adds time, so the minimum is its most stable estimate.
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

const RunRow* find_unit(const RunRow& row, const ResultsFile& file) {
  if (row.scheme != "osd-bfr")
    for (const RunRow& peer : file.runs)
      if (peer.scheme == "osd-bfr" && peer.status == "ok" && peer.mesh == row.mesh &&
          peer.tessellation == row.tessellation && peer.backend == (row.backend == "vulkan" ? "cpu-mt" : row.backend) &&
          !timing(peer).samples.empty())
        return &peer;
  for (const RunRow& probe : file.runs)
    if (probe.scheme == "calibration" && probe.backend == row.backend && !timing(probe).samples.empty()) return &probe;
  return nullptr;
}

// Each repetition's time in units of the same run's osd-bfr time on the same mesh, tessellation
// and backend; rows without such a peer (the peer itself) in units of the calibration probe run
// beside them (bench --rounds), or failing that of the machine's bandwidth probe.
std::optional<Normalised> normalise(const RunRow& row, const ResultsFile& file) {
  const TimeStats& t = timing(row);
  const bool paired = file.rounds > 0;
  if (const RunRow* unit = find_unit(row, file)) {
    const std::string by = unit->scheme == "osd-bfr" ? "osd-bfr" : "write probe";
    return Normalised{divided(t.samples, timing(*unit).samples, paired), paired ? by + ", paired" : by};
  }
  const double bw = row.backend == "cpu-mt"   ? file.machine.write_bandwidth_mt_gbs
                    : row.backend == "vulkan" ? file.machine.gpu_write_bandwidth_gbs
                                              : file.machine.write_bandwidth_gbs;
  if (bw <= 0) return std::nullopt;
  Normalised n{{}, "bandwidth probe"};
  for (double s : t.samples) n.samples.push_back(s * bw);
  return n;
}

}  // namespace

bool GateReport::failed() const {
  return !problems.empty() || std::any_of(entries.begin(), entries.end(), [](const GateEntry& e) { return e.regression; });
}

GateConfig read_gate_config(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open gate configuration");
  GateConfig c;
  try {
    nlohmann::json j;
    in >> j;
    c.alpha = j.value("alpha", c.alpha);
    c.min_repetitions = j.value("min_repetitions", c.min_repetitions);
    c.default_threshold = j.value("default_threshold", c.default_threshold);
    for (const auto& t : j.value("thresholds", nlohmann::json::array()))
      c.thresholds.emplace_back(t.at("match").get<std::string>(), t.at("threshold").get<double>());
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, std::string("malformed gate configuration: ") + e.what());
  }
  return c;
}

GateReport run_gate(const ResultsFile& baseline, const ResultsFile& current, const GateConfig& config) {
  GateReport report;
  std::map<std::string, const RunRow*> base;
  for (const RunRow& r : baseline.runs)
    if (r.status == "ok") base[name_of(r)] = &r;
  for (const RunRow& cur : current.runs) {
    if (cur.status != "ok" || cur.scheme == "calibration") continue;
    const auto it = base.find(name_of(cur));
    if (it == base.end()) continue;
    const RunRow& old = *it->second;
    GateEntry e;
    e.name = name_of(cur);
    const int reps = std::min(timing(cur).reps, timing(old).reps);
    if (reps < config.min_repetitions || timing(cur).samples.size() < size_t(config.min_repetitions) ||
        timing(old).samples.size() < size_t(config.min_repetitions)) {
      report.problems.push_back(e.name + ": " + std::to_string(reps) + " repetitions, the gate needs " +
                                std::to_string(config.min_repetitions));
      continue;
    }
    const auto a = normalise(old, baseline), b = normalise(cur, current);
    if (!a || !b || a->by != b->by) {
      report.problems.push_back(e.name + ": no common normaliser (osd-bfr peer or bandwidth probe) in both runs");
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
