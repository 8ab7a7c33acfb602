// The gate's view over commits, computed here once: each gated benchmark's normalised time in each
// results file (one per commit, oldest first) and, from each file to the next, the gate's own
// verdict: run_gate on the pair, so the same normaliser (a Vulkan row over its own cpu-mt row where
// ci/gate.json says so), threshold, repetitions and U test as `subdivbench gate`.
// reports/report.py draws it; nothing is normalised or judged there.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "harness/gate/gate.h"
#include "harness/results/results.h"

namespace sdb {

struct HistorySpan {
  double median = 0, low = 0, high = 0;  // of the normalised repetitions (gate.h normalised_times)
};

// From the file before to this one.
struct HistoryStep {
  std::string verdict;  // "slower" | "faster" | "same" as the gate judges; "gap": the gate fails on it; "not judged"
  double change = 0;    // median normalised figure, this file / the one before - 1
  double p_value = 1;
  double threshold = 0;
  std::string why;  // for a gap or a pair the gate cannot judge: its words
};

struct HistoryBenchmark {
  std::string name;        // scheme/backend/mesh/level
  std::string scheme;      // as the row spells it
  std::string normaliser;  // as the gate names it, from the newest file that has one
  std::vector<std::optional<HistorySpan>> spans;  // per file; none where the file has no ok, normalisable row
  std::vector<std::optional<HistoryStep>> steps;  // per file; none for the first and where neither file has the row
  bool slower_somewhere() const;
};

struct History {
  std::vector<std::string> labels;  // per file: its commit (12 characters), " #n" where one repeats
  // Those the gate calls slower (or fails on) somewhere first, then the registry's order.
  std::vector<HistoryBenchmark> benchmarks;
};

History make_history(const std::vector<ResultsFile>& files, const GateConfig& config);
nlohmann::json history_json(const History& history);

}  // namespace sdb
