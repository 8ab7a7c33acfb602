// merge_results over shards of one sweep, the refusals that keep a merged report honest, and the
// `shard` and `paired` fields surviving a write and a read.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "harness/core/errors.h"
#include "harness/core/input_error_of_file.h"
#include "harness/results/results.h"
#include "harness/results/results_merge.h"

using namespace sdb;
namespace fs = std::filesystem;

namespace {

RunRow row(const std::string& scheme, const std::string& mesh, int level) {
  RunRow r;
  r.scheme = r.spec = scheme;
  r.mesh = mesh;
  r.level = level;
  r.triangles = 1000L * level;
  return r;
}

ResultsFile shard(int index, int count, std::vector<RunRow> rows) {
  ResultsFile f;
  f.machine.cpu_model = "test cpu";
  f.machine.git_commit = "abc123";
  f.created = "2026-12-0" + std::to_string(index + 1) + "T00:00:00Z";
  f.shard = ShardInfo{index, count};
  f.runs = std::move(rows);
  return f;
}

std::vector<ResultsFile> three_shards() {
  return {shard(0, 3, {row("osd-uniform", "cube", 1), row("osd-uniform", "cube", 2)}),
          shard(1, 3, {row("c-patch", "cube", 1)}),
          shard(2, 3, {row("c-patch", "cube", 2), row("osd-bfr", "torus", 3)})};
}

const std::vector<std::string> kNames = {"a/results.json", "b/results.json", "c/results.json"};

// The message of the InputError merge_results raises, or "" when it merges.
std::string merge_error(const std::vector<ResultsFile>& files, const MergeOptions& options = {}) {
  try {
    merge_results(files, kNames, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

PairedCell cell(const std::string& mesh) {
  PairedCell c;
  c.mesh = mesh;
  c.row = {"c-patch", Backend::CpuMt, 3, 123456};
  c.peer = {"osd-uniform", Backend::Cpu, 2, 98304};
  c.rounds = 3;
  c.rate_ratio_per_round = {1.5, 1.25, 1.75};
  c.rate_ratio_median = 1.5, c.rate_ratio_min = 1.25, c.rate_ratio_max = 1.75;
  c.time_ms_median = 4.5, c.peer_time_ms_median = 6.25;
  return c;
}

}  // namespace

TEST(MergeResults, ThreeShardsGiveEveryRowOnceWithoutAShard) {
  std::vector<ResultsFile> files = three_shards();
  files[1].paired.push_back(cell("cube"));
  const ResultsFile merged = merge_results(files, kNames);
  std::set<std::string> names;
  for (const RunRow& r : merged.runs) names.insert(r.name());
  std::set<std::string> expected;
  for (const ResultsFile& f : files)
    for (const RunRow& r : f.runs) expected.insert(r.name());
  EXPECT_EQ(merged.runs.size(), 5u);
  EXPECT_EQ(names, expected);
  EXPECT_FALSE(merged.shard.has_value());
  ASSERT_EQ(merged.paired.size(), 1u);
  EXPECT_EQ(merged.paired[0].mesh, "cube");
  EXPECT_EQ(merged.machine.git_commit, "abc123");
  EXPECT_EQ(merged.created, "2026-12-03T00:00:00Z");
}

TEST(MergeResults, RefusesAnotherCommitNamingTheFile) {
  std::vector<ResultsFile> files = three_shards();
  files[2].machine.git_commit = "def456";
  const std::string message = merge_error(files);
  EXPECT_EQ(message.rfind("c/results.json: ", 0), 0u) << message;
  EXPECT_NE(message.find("def456"), std::string::npos) << message;
  EXPECT_EQ(merge_error(files, {.allow_mixed = true}), "");
}

TEST(MergeResults, RefusesAnotherMachineNamingTheFile) {
  std::vector<ResultsFile> files = three_shards();
  files[1].machine.cpu_model = "other cpu";
  const std::string message = merge_error(files);
  EXPECT_EQ(message.rfind("b/results.json: ", 0), 0u) << message;
  EXPECT_NE(message.find("other cpu"), std::string::npos) << message;
  EXPECT_EQ(merge_error(files, {.allow_mixed = true}), "");
}

TEST(MergeResults, RefusesARowInTwoFiles) {
  std::vector<ResultsFile> files = three_shards();
  files[2].runs.push_back(row("osd-uniform", "cube", 2));
  const std::string message = merge_error(files);
  EXPECT_EQ(message.rfind("c/results.json: ", 0), 0u) << message;
  EXPECT_NE(message.find("a/results.json"), std::string::npos) << message;
  // Mixing allows other machines, never a row counted twice.
  EXPECT_NE(merge_error(files, {.allow_mixed = true}), "");
}

TEST(MergeResults, RefusesTwoFilesClaimingOneShard) {
  std::vector<ResultsFile> files = three_shards();
  files[1].shard->index = 0;
  const std::string message = merge_error(files);
  EXPECT_EQ(message.rfind("b/results.json: ", 0), 0u) << message;
  EXPECT_NE(message.find("shard 0"), std::string::npos) << message;
}

TEST(MergeResults, KeepsRoundsOnlyWhenEveryFileHasTheSame) {
  std::vector<ResultsFile> files = three_shards();
  for (ResultsFile& f : files) f.rounds = 5;
  EXPECT_EQ(merge_results(files, kNames).rounds, 5);
  files[2].rounds = 3;
  EXPECT_EQ(merge_results(files, kNames).rounds, 0);
}

TEST(Results, ShardAndPairedRoundTrip) {
  ResultsFile r = shard(1, 4, {row("c-patch", "cube", 2)});
  r.paired = {cell("cube"), cell("bunny")};
  const fs::path p = fs::temp_directory_path() / ("sdb_merge_test_" + std::to_string(::getpid()) + ".json");
  write_results(r, p.string());
  const ResultsFile back = read_results(p.string());
  fs::remove(p);
  ASSERT_TRUE(back.shard.has_value());
  EXPECT_EQ(back.shard->index, 1);
  EXPECT_EQ(back.shard->count, 4);
  ASSERT_EQ(back.paired.size(), 2u);
  const PairedCell& c = back.paired[1];
  EXPECT_EQ(c.mesh, "bunny");
  EXPECT_EQ(c.row.scheme, "c-patch");
  EXPECT_EQ(c.row.backend, Backend::CpuMt);
  EXPECT_EQ(c.row.level, 3);
  EXPECT_EQ(c.row.triangles, 123456);
  EXPECT_EQ(c.peer.scheme, "osd-uniform");
  EXPECT_EQ(c.peer.backend, Backend::Cpu);
  EXPECT_EQ(c.peer.triangles, 98304);
  EXPECT_EQ(c.rounds, 3);
  EXPECT_EQ(c.rate_ratio_per_round, (std::vector<double>{1.5, 1.25, 1.75}));
  EXPECT_DOUBLE_EQ(c.rate_ratio_median, 1.5);
  EXPECT_DOUBLE_EQ(c.rate_ratio_min, 1.25);
  EXPECT_DOUBLE_EQ(c.rate_ratio_max, 1.75);
  EXPECT_DOUBLE_EQ(c.time_ms_median, 4.5);
  EXPECT_DOUBLE_EQ(c.peer_time_ms_median, 6.25);
}

TEST(Results, FilesWithoutShardOrPairedReadAsBefore) {
  const fs::path p = fs::temp_directory_path() / ("sdb_merge_test_old_" + std::to_string(::getpid()) + ".json");
  ResultsFile plain;
  write_results(plain, p.string());
  const ResultsFile back = read_results(p.string());
  fs::remove(p);
  EXPECT_FALSE(back.shard.has_value());
  EXPECT_TRUE(back.paired.empty());
}

TEST(Results, RefusesAShardOutsideItsCount) {
  const std::string message = input_error_of_file("sdb_merge_test_bad.json",
                                                  R"({"schema": 1, "runs": [], "shard": {"index": 3, "count": 3}})",
                                                  [](const std::string& path) { read_results(path); });
  EXPECT_NE(message.find("'shard' must have 0 <= index < count"), std::string::npos) << message;
}
