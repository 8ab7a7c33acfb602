// results.json reader (harness/bench/results.cpp). A file it accepts must also survive what the
// verbs then do with it: written again (report re-writes every input) and read back to the same
// rows, and judged by the gate against itself without a crash or a hang. It must hold only
// figures a run can give (checked here independently of results_check.cpp: no negative time, a
// median inside its range, no rate without triangles, counts of -1 or more, paired ratios
// positive), one row per run; and the gate must pass it against itself and fail it, naming the
// row, when a benchmark is taken out.
#include <cmath>
#include <set>

#include "harness/gate/gate.h"
#include "harness/results/results.h"
#include "tests/fuzz/contract.h"

namespace {

bool within(double median, double lo, double hi) {
  return std::isnan(median) || std::isnan(lo) || std::isnan(hi) || (lo <= median * (1 + 1e-9) + 1e-300 && median <= hi * (1 + 1e-9) + 1e-300);
}

void require_possible_time(const sdb::TimeStats& t) {
  for (double x : {t.median, t.min, t.max}) sdb::fuzz::require(!(x < 0), "a negative time was accepted");
  for (double x : t.samples) sdb::fuzz::require(!(x < 0), "a negative sample was accepted");
  sdb::fuzz::require(within(t.median, t.min, t.max), "a median outside its own range was accepted");
}

void require_possible_figures(const sdb::ResultsFile& r) {
  std::set<std::string> names;
  for (const sdb::RunRow& row : r.runs) {
    sdb::fuzz::require(names.insert(row.name()).second, "a run with two rows was accepted");
    require_possible_time(row.time_ms);
    if (row.gpu_time_ms) require_possible_time(*row.gpu_time_ms);
    sdb::fuzz::require(row.triangles >= 0 && row.vertices >= 0 && row.bytes_out >= 0, "a negative count was accepted");
    sdb::fuzz::require(!(row.triangles == 0 && row.triangle_rate_mtris > 0), "a triangle rate at 0 triangles was accepted");
    sdb::fuzz::require(!(row.triangle_rate_mtris < 0), "a negative triangle rate was accepted");
    sdb::fuzz::require(row.watertight.open_edges >= -1 && row.watertight.ray_cracks >= -1, "a count below -1 was accepted");
  }
  for (const sdb::PairedCell& c : r.paired) {
    for (double x : c.rate_ratio_per_round) sdb::fuzz::require(!(x <= 0), "a paired ratio of 0 or less was accepted");
    sdb::fuzz::require(!(c.rate_ratio_median <= 0), "a paired median of 0 or less was accepted");
    sdb::fuzz::require(within(c.rate_ratio_median, c.rate_ratio_min, c.rate_ratio_max),
                       "a paired median outside its own range was accepted");
  }
}

// Against itself every ok benchmark is matched; with the first one taken out the gate fails,
// naming it, whatever the machines.
void require_gate_names_a_missing_benchmark(const sdb::ResultsFile& r) {
  const sdb::GateReport same = sdb::run_gate(r, r, sdb::GateConfig{});
  sdb::fuzz::require(same.gaps.empty() && same.new_rows.empty(), "the gate found a gap between a file and itself");
  for (size_t i = 0; i < r.runs.size(); ++i) {
    if (r.runs[i].status != sdb::RunStatus::Ok || r.runs[i].scheme == sdb::kCalibrationScheme) continue;
    sdb::ResultsFile fewer = r;
    fewer.runs.erase(fewer.runs.begin() + long(i));
    const sdb::GateReport report = sdb::run_gate(r, fewer, sdb::GateConfig{});
    sdb::fuzz::require(report.failed(), "the gate passed a run with a baseline benchmark missing");
    sdb::fuzz::require(report.gaps.size() == 1 && report.gaps[0].name == r.runs[i].name(),
                       "the gate did not name the missing benchmark");
    return;
  }
}

void require_round_trip(const sdb::ResultsFile& first) {
  const std::string again = sdb::fuzz::scratch_path("-rewritten.json");
  sdb::write_results(first, again);
  const sdb::ResultsFile second = sdb::read_results(again);
  sdb::fuzz::require(second.runs.size() == first.runs.size(), "results written and read back lost or gained rows");
  for (size_t i = 0; i < first.runs.size(); ++i)
    sdb::fuzz::require(second.runs[i].name() == first.runs[i].name(), "results written and read back renamed a row");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = sdb::fuzz::write_input_file(sdb::fuzz::as_text(data, size), ".json");
  sdb::fuzz::holds_contract(path, [&] {
    const sdb::ResultsFile r = sdb::read_results(path);
    sdb::fuzz::require(r.schema == sdb::kResultsSchema, "a results file of another schema was read");
    for (const sdb::RunRow& row : r.runs) (void)sdb::row_json(row);
    require_possible_figures(r);
    require_gate_names_a_missing_benchmark(r);
    // Rows the reader accepted must be written back without an InputError too.
    try {
      require_round_trip(r);
    } catch (const sdb::InputError& e) {
      sdb::fuzz::finding(std::string("accepted results cannot be written and read back: ") + e.what());
    }
  });
  return 0;
}
