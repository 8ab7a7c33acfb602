#include "harness/results/results_merge.h"

#include <map>
#include <stdexcept>

#include "harness/core/errors.h"

namespace sdb {
namespace {

// Why `file` cannot be merged with `first` (the files' machines), or "" when it can.
std::string machine_mismatch(const MachineInfo& first, const MachineInfo& file, const std::string& first_name) {
  if (file.git_commit != first.git_commit)
    return "built from commit '" + file.git_commit + "', not '" + first.git_commit + "' as " + first_name +
           " (--allow-mixed to merge anyway)";
  if (file.cpu_model != first.cpu_model)
    return "measured on '" + file.cpu_model + "', not '" + first.cpu_model + "' as " + first_name +
           " (--allow-mixed to merge anyway)";
  return "";
}

}  // namespace

ResultsFile merge_results(const std::vector<ResultsFile>& files, const std::vector<std::string>& names,
                          const MergeOptions& options) {
  if (files.size() != names.size()) throw std::invalid_argument("merge_results: one name per file");
  ResultsFile merged;
  if (files.empty()) return merged;
  merged.machine = files[0].machine;
  merged.rounds = files[0].rounds;
  std::map<std::string, size_t> row_owner;    // row name -> the file it came from
  std::map<int, size_t> shard_owner;          // shard index -> the file claiming it
  for (size_t i = 0; i < files.size(); ++i) {
    const ResultsFile& f = files[i];
    if (!options.allow_mixed) {
      const std::string why = machine_mismatch(files[0].machine, f.machine, names[0]);
      if (!why.empty()) throw InputError(names[i], why);
    }
    if (f.shard) {
      const auto [it, fresh] = shard_owner.emplace(f.shard->index, i);
      if (!fresh)
        throw InputError(names[i], "claims shard " + std::to_string(f.shard->index) + " as " + names[it->second] + " does");
    }
    for (const RunRow& row : f.runs) {
      const auto [it, fresh] = row_owner.emplace(row.name(), i);
      if (!fresh) throw InputError(names[i], "row " + row.name() + " is also in " + names[it->second]);
      merged.runs.push_back(row);
    }
    merged.paired.insert(merged.paired.end(), f.paired.begin(), f.paired.end());
    // Rounds only describe the merged file when every part was measured with the same number.
    if (f.rounds != merged.rounds) merged.rounds = 0;
    if (f.created > merged.created) merged.created = f.created;  // ISO 8601 in UTC sorts as text
  }
  return merged;
}

}  // namespace sdb
