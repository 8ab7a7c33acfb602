// The order of a pass's work groups (pass_plan.h, interleave_by_cost): lavapipe gives each of its
// T threads one contiguous 1/T of a dispatch, so the costly work must be spread over every stretch.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "schemes/fragments/pass_plan.h"

namespace {

using sdb::fragments::interleave_by_cost;
using sdb::fragments::WorkItem;

// Cost of each of `t` contiguous parts, as lp_cs_tpool splits them (the remainder one at a time
// at the end, which the parts below ignore: n is a multiple of t).
std::vector<uint64_t> part_costs(const std::vector<WorkItem>& items, size_t t) {
  std::vector<uint64_t> parts(t, 0);
  const size_t per = items.size() / t;
  for (size_t i = 0; i < per * t; ++i) parts[i / per] += items[i].cost;
  return parts;
}

// Every item once; a batch's items together and in their order.
TEST(InterleaveByCost, KeepsEveryItemOnceAndABatchsItemsTogether) {
  std::vector<WorkItem> items;
  for (uint32_t i = 0; i < 50; ++i) items.push_back({i / 7, i % 7, uint64_t((i * 37) % 11)});
  const std::vector<WorkItem> out = interleave_by_cost(items);
  ASSERT_EQ(out.size(), items.size());
  std::vector<std::pair<uint32_t, uint32_t>> seen, expected;
  for (size_t i = 0; i < out.size(); ++i) {
    seen.emplace_back(out[i].batch, out[i].chunk);
    expected.emplace_back(items[i].batch, items[i].chunk);
    if (i == 0) continue;
    if (out[i].batch == out[i - 1].batch) {
      EXPECT_EQ(out[i].chunk, out[i - 1].chunk + 1);
    } else {
      for (size_t k = 0; k + 1 < i; ++k) EXPECT_NE(out[k].batch, out[i].batch) << "batch " << out[i].batch << " split";
    }
  }
  std::sort(seen.begin(), seen.end());
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(seen, expected);
}

// Batches in shape order: the 8 costly vertex-patch batches last, as on Blub. In that order one
// thread of two gets all of them; interleaved, every part of 2, 4 or 8 gets its share.
TEST(InterleaveByCost, SpreadsTheCostlyBatchesOverEveryPart) {
  std::vector<WorkItem> items;
  for (uint32_t i = 0; i < 56; ++i) items.push_back({0, i, 1});
  for (uint32_t i = 56; i < 64; ++i) items.push_back({0, i, 100});
  EXPECT_EQ(part_costs(items, 2), (std::vector<uint64_t>{32, 824}));
  const std::vector<WorkItem> out = interleave_by_cost(items);
  for (size_t t : {2, 4, 8}) {
    const std::vector<uint64_t> parts = part_costs(out, t);
    for (uint64_t c : parts) EXPECT_EQ(c, 856 / t) << t << " parts";
  }
}

TEST(InterleaveByCost, BalancesRandomCostsWithinAFewPercent) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> cost(1, 1000);
  std::vector<WorkItem> items;
  for (uint32_t i = 0; i < 1000; ++i) items.push_back({0, i, uint64_t(cost(rng))});
  std::sort(items.begin(), items.end(), [](const WorkItem& a, const WorkItem& b) { return a.cost < b.cost; });
  const std::vector<WorkItem> out = interleave_by_cost(items);
  for (size_t t : {2, 4, 8}) {
    const std::vector<uint64_t> parts = part_costs(out, t);
    const auto [lo, hi] = std::minmax_element(parts.begin(), parts.end());
    EXPECT_LT(double(*hi) / double(*lo), 1.05) << t << " parts";
    const std::vector<uint64_t> sorted_parts = part_costs(items, t);
    EXPECT_GT(double(sorted_parts.back()) / double(sorted_parts.front()), 2.0) << "the input was balanced already";
  }
}

}  // namespace
