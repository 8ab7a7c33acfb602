// The performance gate: compares a current results.json with a baseline on figures that a slower
// or busier machine does not move: each repetition's time over its peer's (the row's `peer`, from
// the scheme's SchemeInfo) on the same mesh and tessellation in the same round; rows without a
// peer over the calibration probe's; rows a `normalisers` entry names over the same scheme, mesh
// and level on another backend (a Vulkan row over its own cpu-mt row: lavapipe runs on the same
// cores). A benchmark regresses when the change is beyond its threshold AND a two-sided
// Mann-Whitney U test says it is significant.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harness/results/results.h"
#include "harness/results/run_spec.h"

namespace sdb {

struct GateConfig {
  double alpha = 0.05;
  int min_repetitions = 9;
  double default_threshold = 0.25;  // relative slowdown of the normalised figure
  std::vector<std::pair<std::string, double>> thresholds;  // (name regex, threshold), first match wins
  // (name regex, backend), first match wins: the row over its own scheme, mesh and level on that
  // backend in the same round, instead of over its peer.
  std::vector<std::pair<std::string, Backend>> normalisers;
  std::vector<RunSpec> workload;  // what scripts/gate benchmarks (`bench --workload FILE`)
};

// Reads ci/gate.json; throws InputError on a malformed file, a bad threshold pattern or a
// workload entry that is not scheme/backend/mesh/level.
GateConfig read_gate_config(const std::string& path);

struct GateEntry {
  std::string name;        // scheme/backend/mesh/level
  std::string normaliser;  // the peer's name, "write probe" or "bandwidth probe" (", paired" by round)
  double change = 0;       // median normalised figure, current / baseline - 1
  double p_value = 1;
  double threshold = 0;
  bool regression = false, improvement = false;
};

// A baseline benchmark the current file has no ok row for: it crashed or failed its checks,
// became unsupported, or is not there at all (dropped, or renamed: its new name is then among
// GateReport::new_rows). A gate that passed such a run would pass a benchmark that stopped running.
struct GateGap {
  std::string name;  // the baseline's run name
  std::string why;   // "failed: crashed during execute: ...", "unsupported: ...", "missing from the current file"
};

struct GateReport {
  std::vector<GateEntry> entries;
  std::vector<std::string> problems;  // benchmarks that cannot be judged (too few repetitions, ...)
  std::vector<GateGap> gaps;          // fail the gate on any machine
  std::vector<std::string> new_rows;  // ok current rows without a baseline row: reported, not judged
  // Set when the baseline was recorded on another processor or core count: the ratios between
  // kernels move with the processor (measured: the AMD EPYC baseline read on an Intel Xeon gave
  // +44% to +90% on rows nothing had touched, identical instruction counts), so its verdicts are
  // shown but fail nothing; the instruction gate still judges.
  std::string other_machine;
  bool failed() const;
};

GateReport run_gate(const ResultsFile& baseline, const ResultsFile& current, const GateConfig& config);

// A row's repetitions in the units the gate compares: each over its normaliser's (its own row on
// the backend `config` names, else its peer, else the write probe) in the same round when the file
// went in rounds, else over the normaliser's fastest; rows with none, times the bandwidth probe.
// `by` names the normaliser as GateEntry::normaliser does. Nothing where the normaliser is missing.
struct NormalisedTimes {
  std::vector<double> samples;
  std::string by;
};
std::optional<NormalisedTimes> normalised_times(const RunRow& row, const ResultsFile& file, const GateConfig& config);

// Per-machine baselines (ci/baselines/): a file name for a baseline recorded on `m`, its processor
// and core count in lower case with every other character a dash ("intel-r-xeon-r-processor-2c"),
// and the path of the first of `files` (results.json files, read in the order given) recorded on
// the same processor and core count as `current`, or nothing.
std::string machine_baseline_name(const MachineInfo& m);
std::optional<std::string> baseline_for_machine(const MachineInfo& current, const std::vector<std::string>& files);

}  // namespace sdb
