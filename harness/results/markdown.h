// Markdown tables, as the paper tables and reports print them: a header row, then rows of cells;
// a '|' inside a cell is written as '/', so that no cell can break the table.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace sdb {

class MarkdownTable {
 public:
  explicit MarkdownTable(std::vector<std::string> header) : header_(std::move(header)) {}
  // Short rows are padded with empty cells to the header's width.
  void add_row(std::vector<std::string> cells) { rows_.push_back(std::move(cells)); }
  size_t rows() const { return rows_.size(); }
  void write(std::ostream& out) const;

 private:
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

}  // namespace sdb
