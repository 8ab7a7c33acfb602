// Gate configuration reader (harness/bench/gate.cpp, read_gate_config). A configuration it accepts
// must hold values the gate can judge with (a significance level in (0, 1), at least one
// repetition, finite non-negative thresholds, run names in the workload) and must drive the gate
// over a fixed pair of results (rows with 0, 3 and 12 samples, with and without a peer) without a
// crash or a hang; and none may let it pass a run in which a baseline benchmark has no row.
#include <cmath>

#include "harness/gate/gate.h"
#include "tests/fuzz/contract.h"

namespace {

sdb::RunRow row(const std::string& scheme, const std::string& peer, int samples, double ms) {
  sdb::RunRow r;
  r.scheme = r.spec = scheme;
  r.mesh = "cube";
  r.level = 3;
  r.tessellation = 8;
  r.peer = peer;
  if (!peer.empty()) r.peer_backend = sdb::Backend::Cpu;
  r.time_ms.reps = samples;
  for (int i = 0; i < samples; ++i) r.time_ms.samples.push_back(ms * (1 + 0.01 * i));
  if (samples) r.time_ms.median = r.time_ms.samples[samples / 2];
  return r;
}

sdb::ResultsFile results(double scale) {
  sdb::ResultsFile f;
  f.machine.write_bandwidth_gbs = 10;
  f.runs = {row("osd-bfr", "", 12, 2.0), row("cpatch-2pass", "osd-bfr", 12, 1.0 * scale),
            row("osd-uniform", "osd-bfr", 3, 4.0 * scale), row("embree-subdiv", "osd-bfr", 0, 0),
            row(sdb::kCalibrationScheme, "", 12, 1.0)};
  return f;
}

void require_judgeable(const sdb::GateConfig& c) {
  sdb::fuzz::require(c.alpha > 0 && c.alpha < 1, "accepted a significance level outside (0, 1)");
  sdb::fuzz::require(c.min_repetitions >= 1, "accepted fewer than one repetition");
  sdb::fuzz::require(std::isfinite(c.default_threshold) && c.default_threshold >= 0, "accepted a bad default threshold");
  for (const auto& [pattern, threshold] : c.thresholds)
    sdb::fuzz::require(std::isfinite(threshold) && threshold >= 0, "accepted a bad threshold");
}

}  // namespace

namespace {

// The baseline without its cpatch-2pass row: whatever a configuration says, a benchmark that
// stopped running fails the gate, named.
sdb::ResultsFile without_method() {
  sdb::ResultsFile f = results(1.0);
  f.runs.erase(f.runs.begin() + 1);
  return f;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const sdb::ResultsFile baseline = results(1.0), current = results(1.5), dropped = without_method();
  const std::string path = sdb::fuzz::write_input_file(sdb::fuzz::as_text(data, size), ".json");
  sdb::fuzz::holds_contract(path, [&] {
    const sdb::GateConfig c = sdb::read_gate_config(path);
    require_judgeable(c);
    const sdb::GateReport report = sdb::run_gate(baseline, current, c);
    for (const sdb::GateEntry& e : report.entries)
      sdb::fuzz::require(!(e.p_value < 0) && !(e.p_value > 1), "the gate gave a p-value outside [0, 1]");
    const sdb::GateReport gap = sdb::run_gate(baseline, dropped, c);
    sdb::fuzz::require(gap.failed() && gap.gaps.size() == 1 && gap.gaps[0].name == "cpatch-2pass/cpu/cube/3",
                       "a configuration let the gate pass a baseline benchmark that has no current row");
  });
  return 0;
}
