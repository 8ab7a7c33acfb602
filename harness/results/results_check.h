// What a results file may hold (harness/bench/README.md, "What each field may hold"): the figures a
// measurement can give, so that no reader (report, gate, resume) prints an impossible one as a
// fact. NaN is "not measured" everywhere and always allowed; a figure that is a number must be
// one a run can produce: no negative time, count or rate, a median inside its own range, no
// triangle rate without triangles, a machine section.
#pragma once

#include <string>

#include "harness/results/results.h"

namespace sdb {

// Why `row` cannot have been measured ("time_ms: median 5 outside its range 1..2"), or "".
std::string impossible_row(const RunRow& row);
// The same for a paired summary cell.
std::string impossible_paired_cell(const PairedCell& cell);

// Throws InputError naming `path` and the first impossible row or cell, by position and name
// ("runs[3] osd-bfr/cpu/cube/2: ..."), or the missing machine section.
void check_results(const ResultsFile& results, const std::string& path, bool has_machine);

}  // namespace sdb
