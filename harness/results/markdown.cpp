#include "harness/results/markdown.h"

#include <algorithm>

namespace sdb {
namespace {

void write_row(std::ostream& out, const std::vector<std::string>& cells, size_t width) {
  out << "|";
  for (size_t i = 0; i < width; ++i) {
    std::string c = i < cells.size() ? cells[i] : "";
    std::replace(c.begin(), c.end(), '|', '/');
    out << " " << c << " |";
  }
  out << "\n";
}

}  // namespace

void MarkdownTable::write(std::ostream& out) const {
  write_row(out, header_, header_.size());
  out << "|";
  for (size_t i = 0; i < header_.size(); ++i) out << "---|";
  out << "\n";
  for (const auto& r : rows_) write_row(out, r, header_.size());
}

}  // namespace sdb
