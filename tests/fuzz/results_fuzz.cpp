// results.json reader (harness/bench/results.cpp). A file it accepts must also survive what the
// verbs then do with it: written again (report re-writes every input) and read back to the same
// rows, and judged by the gate against itself without a crash or a hang.
#include "harness/bench/gate.h"
#include "harness/bench/results.h"
#include "tests/fuzz/contract.h"

namespace {

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
    (void)sdb::run_gate(r, r, sdb::GateConfig{});
    // Rows the reader accepted must be written back without an InputError too.
    try {
      require_round_trip(r);
    } catch (const sdb::InputError& e) {
      sdb::fuzz::finding(std::string("accepted results cannot be written and read back: ") + e.what());
    }
  });
  return 0;
}
