// What every paper table (harness/core/paper_table.h) writes the same way: the device line, the
// number format, and the Markdown file beside the printed table.
#pragma once

#include <ostream>
#include <string>

#include "harness/core/paper_table.h"

namespace sdb {

// The Vulkan device in one line; on a CPU implementation (lavapipe) it says that absolute frame
// rates are not comparable with the papers' GPUs.
std::string device_line();
// Writes `markdown` to <out_dir>/<id>.md and to `out`; returns the path.
std::string publish(const PaperTableOptions& options, const std::string& id, const std::string& markdown,
                    std::ostream& out);
std::string fixed(double value, int decimals);

}  // namespace sdb
