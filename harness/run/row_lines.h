// One measured row as `run` and `validate` print it: the name padded to a column, then the figures
// (triangles, time, rate, bandwidth, the watertight and deviation checks, why it failed).
#pragma once

#include <string>

#include "harness/results/results.h"

namespace sdb {

std::string row_head(const RunRow& row);
std::string row_figures(const RunRow& row);
void print_row(const RunRow& row);  // head and figures on one line of standard output

}  // namespace sdb
