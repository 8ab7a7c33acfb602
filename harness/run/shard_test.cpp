// `run --shard I/N`: the shards of a selection partition it whatever the order it was spelled in,
// and N shards measured separately and merged equal the unsharded run's rows. Also the quick
// set's choice of levels.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include "harness/run/plan.h"
#include "harness/run/run_set.h"
#include "harness/core/errors.h"
#include "harness/results/results_merge.h"

using namespace sdb;
namespace fs = std::filesystem;

namespace {

std::vector<RunSpec> some_runs() {
  std::vector<RunSpec> runs;
  for (const char* scheme : {"osd-uniform", "osd-bfr", "c-patch"})
    for (const char* mesh : {"cube", "torus", "pole5"})
      for (int level : {1, 2, 3}) runs.push_back({scheme, mesh, Backend::Cpu, level});
  return runs;
}

std::vector<std::string> names(const std::vector<RunSpec>& runs) {
  std::vector<std::string> n;
  for (const RunSpec& r : runs) n.push_back(r.name());
  return n;
}

// A small selection: two fast peers, two built-in meshes, levels up to a few thousand triangles.
RunSelection small_selection(int shard_index = 0, int shard_count = 1) {
  RunSelection s;
  s.selection.schemes = {"osd-uniform", "osd-bfr"};
  s.selection.meshes = {"cube", "torus-8x8"};
  s.selection.backends = {"cpu"};
  s.selection.max_triangles = 3000;
  s.selection.shard_index = shard_index, s.selection.shard_count = shard_count;
  s.reps = 1;
  s.rays = 2000;
  return s;
}

ResultsFile run_in(const fs::path& dir, const RunSelection& selection) {
  RunSet set = RunSet::start(dir.string(), selection, false);
  set.measure_remaining([](const RunRow&) {});
  return set.results();
}

// The figures of a row that do not depend on timing.
std::string deterministic(const RunRow& r) {
  return std::to_string(r.triangles) + " " + std::to_string(r.vertices) + " open " + std::to_string(r.watertight.open_edges) +
         " cracks " + std::to_string(r.watertight.ray_cracks) + "/" + std::to_string(r.watertight.rays) + " dev " +
         std::to_string(r.deviation.pos_max_pct) + " " + std::to_string(r.deviation.pos_p95_pct) + " " +
         std::to_string(r.deviation.normal_max_deg) + " " + std::string(to_string(r.status));
}

std::map<std::string, std::string> by_name(const std::vector<RunRow>& rows) {
  std::map<std::string, std::string> m;
  for (const RunRow& r : rows) m[r.name()] = deterministic(r);
  return m;
}

}  // namespace

TEST(ShardRuns, PartitionTheRunsWhateverTheirOrder) {
  const std::vector<RunSpec> runs = some_runs();
  std::vector<RunSpec> reversed(runs.rbegin(), runs.rend());
  std::multiset<std::string> all;
  for (int i = 0; i < 4; ++i) {
    const std::vector<RunSpec> shard = shard_runs(runs, i, 4);
    std::vector<std::string> a = names(shard), b = names(shard_runs(reversed, i, 4));
    EXPECT_GE(shard.size(), runs.size() / 4);  // round robin over sorted names: sizes differ by one at most
    EXPECT_LE(shard.size(), runs.size() / 4 + 1);
    std::sort(a.begin(), a.end()), std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b) << "shard " << i << " depends on the order of the selection";
    all.insert(a.begin(), a.end());
  }
  const std::vector<std::string> expected = names(runs);
  EXPECT_EQ(all, std::multiset<std::string>(expected.begin(), expected.end()));
}

TEST(ParseShard, IndexCountsFromZeroAndStaysBelowTheCount) {
  EXPECT_EQ(parse_shard("0/3"), std::make_pair(0, 3));
  EXPECT_EQ(parse_shard("2/3"), std::make_pair(2, 3));
  for (const char* bad : {"3/3", "1/0", "-1/3", "a/3", "1/3/4", "", "1", "9999999/3"}) {
    try {
      parse_shard(bad);
      ADD_FAILURE() << bad << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--shard " + std::string(bad), 0), 0u) << e.what();
    }
  }
}

TEST(ShardRuns, OneShardIsTheWhole) { EXPECT_EQ(names(shard_runs(some_runs(), 0, 1)), names(some_runs())); }

TEST(QuickLevels, NearestAMillionThenNearestAHundredThousand) {
  EXPECT_EQ(quick_levels({{1, 1'000}, {2, 10'000}, {3, 90'000}, {4, 400'000}, {5, 1'600'000}}), (std::vector<int>{3, 5}));
  // The level nearest both is taken for the million; the hundred thousand gets the next nearest.
  EXPECT_EQ(quick_levels({{1, 3'000}, {2, 12'000}, {3, 196'000}}), (std::vector<int>{2, 3}));
  EXPECT_EQ(quick_levels({{7, 500}}), (std::vector<int>{7}));
  EXPECT_TRUE(quick_levels({}).empty());
}

TEST(Shards, ThreeShardsMergedEqualTheUnshardedRun) {
  const fs::path root = fs::temp_directory_path() / ("sdb_shard_test_" + std::to_string(::getpid()));
  fs::remove_all(root);
  const ResultsFile whole = run_in(root / "whole", small_selection());
  ASSERT_GE(whole.runs.size(), 6u);
  EXPECT_FALSE(whole.shard.has_value());

  std::vector<ResultsFile> shards;
  std::vector<std::string> files;
  for (int i = 0; i < 3; ++i) {
    shards.push_back(run_in(root / ("shard" + std::to_string(i)), small_selection(i, 3)));
    ASSERT_TRUE(shards.back().shard.has_value());
    EXPECT_EQ(shards.back().shard->index, i);
    EXPECT_EQ(shards.back().shard->count, 3);
    EXPECT_LT(shards.back().runs.size(), whole.runs.size());
    files.push_back((root / ("shard" + std::to_string(i)) / "results.json").string());
  }
  const ResultsFile merged = merge_results(shards, files);
  fs::remove_all(root);
  EXPECT_EQ(merged.runs.size(), whole.runs.size());
  EXPECT_EQ(by_name(merged.runs), by_name(whole.runs));
  for (const RunRow& r : whole.runs) EXPECT_EQ(r.status, RunStatus::Ok) << r.name() << ": " << r.message;
}
