// One results file from several: the shards of a sweep run on several machines (`run --shard I/N`),
// read back by `report --in a.json --in b.json ...`.
#pragma once

#include <string>
#include <vector>

#include "harness/results/results.h"

namespace sdb {

struct MergeOptions {
  bool allow_mixed = false;  // allow files from different commits or machines
};

// files[i] was read from names[i]. Throws InputError(names[i], reason) naming the first offending
// file: different machine.git_commit or machine.cpu_model than files[0] (unless allow_mixed), the
// same row name (RunRow::name()) in two files, or two files claiming the same shard index.
// The merged file has every file's rows and paired cells in file order, files[0]'s machine, the
// latest creation time and no shard (it is the whole, or as much of it as was given).
ResultsFile merge_results(const std::vector<ResultsFile>& files, const std::vector<std::string>& names,
                          const MergeOptions& options = {});

}  // namespace sdb
