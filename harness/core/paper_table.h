// The papers' tables, reproduced: `subdivbench paper ID` prints the paper's numbers and ours side
// by side (TABLES.md), on the same workload shape, our hardware named, and writes what it made
// (Markdown, PNGs) into the output folder. Each scheme folder registers its papers' tables
// (SDB_REGISTER_PAPER_TABLES, harness/core/registry.h).
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace sdb {

struct PaperTableOptions {
  std::string out_dir = "results/paper";
  int reps = 5;        // timed repetitions per cell
  bool quick = false;  // smaller meshes / fewer cells, for tests
  std::string texture;  // an image a table reads (paper --texture), where it takes one; empty: its own
};

struct PaperTable {
  std::string id;     // e.g. "ni2008-table4"
  std::string title;  // one line
  // Prints the side-by-side table; returns the exit code (0 ok, 1 a check failed).
  std::function<int(const PaperTableOptions&, std::ostream&)> run;
};

}  // namespace sdb
