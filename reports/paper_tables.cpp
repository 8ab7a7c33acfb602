#include "paper_tables.h"

namespace sdb {

// Each scheme folder with paper tables defines one of these (see its paper.cpp).
std::vector<PaperTable> cpatch_paper_tables();
std::vector<PaperTable> geometry_image_paper_tables();

const std::vector<PaperTable>& paper_tables() {
  static const std::vector<PaperTable> tables = [] {
    std::vector<PaperTable> all;
    for (auto& t : cpatch_paper_tables()) all.push_back(std::move(t));
    for (auto& t : geometry_image_paper_tables()) all.push_back(std::move(t));
    return all;
  }();
  return tables;
}

}  // namespace sdb
