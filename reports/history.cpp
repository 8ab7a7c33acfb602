#include "reports/history.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "harness/core/registry.h"
#include "harness/results/statistics.h"

namespace sdb {
namespace {

std::vector<std::string> commit_labels(const std::vector<ResultsFile>& files) {
  std::vector<std::string> labels;
  for (size_t i = 0; i < files.size(); ++i) {
    const std::string& commit = files[i].machine.git_commit;
    std::string label = commit.empty() ? "?" : commit.substr(0, 12);
    if (std::find(labels.begin(), labels.end(), label) != labels.end()) label += " #" + std::to_string(i + 1);
    labels.push_back(label);
  }
  return labels;
}

std::optional<HistorySpan> span_of(const RunRow& row, const ResultsFile& file, const GateConfig& config,
                                   std::string& normaliser) {
  const auto n = normalised_times(row, file, config);
  if (!n || n->samples.empty() ||
      !std::all_of(n->samples.begin(), n->samples.end(), [](double x) { return std::isfinite(x) && x > 0; }))
    return std::nullopt;
  normaliser = n->by;
  const auto [low, high] = std::minmax_element(n->samples.begin(), n->samples.end());
  return HistorySpan{median(n->samples), *low, *high};
}

// The gate's report on files[i - 1] -> files[i], as one step per benchmark it names.
std::map<std::string, HistoryStep> steps_of(const GateReport& report) {
  std::map<std::string, HistoryStep> steps;
  for (const GateEntry& e : report.entries)
    steps[e.name] = {e.regression ? "slower" : e.improvement ? "faster" : "same", e.change, e.p_value, e.threshold, ""};
  for (const GateGap& g : report.gaps) steps[g.name] = {"gap", 0, 1, 0, g.why};
  for (const std::string& p : report.problems) {
    const size_t colon = p.find(": ");
    steps[p.substr(0, colon)] = {"not judged", 0, 1, 0, colon == std::string::npos ? p : p.substr(colon + 2)};
  }
  return steps;
}

size_t registry_rank(const std::string& scheme) {
  const auto& schemes = all_schemes();
  for (size_t i = 0; i < schemes.size(); ++i)
    if (schemes[i]->info().name == scheme) return i;
  return schemes.size();
}

}  // namespace

bool HistoryBenchmark::slower_somewhere() const {
  return std::any_of(steps.begin(), steps.end(),
                     [](const auto& s) { return s && (s->verdict == "slower" || s->verdict == "gap"); });
}

History make_history(const std::vector<ResultsFile>& files, const GateConfig& config) {
  History h{commit_labels(files), {}};
  std::map<std::string, size_t> index;
  auto benchmark = [&](const RunRow& r) -> HistoryBenchmark& {
    const auto [it, added] = index.emplace(r.name(), h.benchmarks.size());
    if (added)
      h.benchmarks.push_back({r.name(), r.scheme, "", std::vector<std::optional<HistorySpan>>(files.size()),
                              std::vector<std::optional<HistoryStep>>(files.size())});
    return h.benchmarks[it->second];
  };
  for (size_t i = 0; i < files.size(); ++i)
    for (const RunRow& r : files[i].runs) {
      if (r.scheme == kCalibrationScheme || r.status != RunStatus::Ok) continue;
      HistoryBenchmark& b = benchmark(r);
      if (!b.spans[i]) b.spans[i] = span_of(r, files[i], config, b.normaliser);
    }
  for (size_t i = 1; i < files.size(); ++i)
    for (auto& [name, step] : steps_of(run_gate(files[i - 1], files[i], config))) {
      const auto it = index.find(name);
      if (it != index.end()) h.benchmarks[it->second].steps[i] = step;
    }
  std::stable_sort(h.benchmarks.begin(), h.benchmarks.end(), [](const HistoryBenchmark& a, const HistoryBenchmark& b) {
    return std::make_tuple(!a.slower_somewhere(), registry_rank(a.scheme), a.name) <
           std::make_tuple(!b.slower_somewhere(), registry_rank(b.scheme), b.name);
  });
  return h;
}

nlohmann::json history_json(const History& history) {
  nlohmann::json benchmarks = nlohmann::json::array();
  for (const HistoryBenchmark& b : history.benchmarks) {
    nlohmann::json spans = nlohmann::json::array(), steps = nlohmann::json::array();
    for (const auto& s : b.spans)
      spans.push_back(s ? nlohmann::json{{"median", s->median}, {"low", s->low}, {"high", s->high}} : nlohmann::json());
    for (const auto& s : b.steps)
      steps.push_back(s ? nlohmann::json{{"verdict", s->verdict}, {"change", s->change}, {"p_value", s->p_value},
                                         {"threshold", s->threshold}, {"why", s->why}}
                        : nlohmann::json());
    benchmarks.push_back({{"name", b.name}, {"scheme", b.scheme}, {"normaliser", b.normaliser}, {"spans", spans},
                          {"steps", steps}});
  }
  return {{"labels", history.labels}, {"benchmarks", benchmarks}};
}

}  // namespace sdb
