#include "schemes/fragments/pass_plan.h"

#include <algorithm>
#include <functional>
#include <map>
#include <numeric>

#include "harness/gpu/gpu.h"

namespace sdb::fragments {
namespace {

// llvmpipe ends every loop of an invocation after 65,535 iterations in all (its
// LP_MAX_TGSI_LOOP_ITERATIONS, shared by every loop of a shader), silently: an invocation that
// would loop longer leaves its output unwritten. So each invocation takes a chunk of a pass's
// entries, small enough that a bound on its loop iterations stays below that; a pass whose single
// entries exceed it (a ring of valence ~100) is refused on llvmpipe, never run short.
constexpr uint64_t kLoopBudget = 60000;

// A kind gets its own dispatch (and pipeline) when it holds kMinKindShare of a pass's entries,
// over all fragments; at most kMaxKinds per pass, the rest go to one dispatch that decides at
// run time. A dispatch costs lavapipe ~0.05 ms, a pipeline a compile.
constexpr double kMinKindShare = 0.02;
constexpr size_t kMaxKinds = 6;

// Per kind, its key and per shape its entries (ascending).
struct EntryKinds {
  std::vector<uint32_t> keys;
  std::vector<std::vector<std::vector<uint32_t>>> lists;
};

EntryKinds plan_kinds(const FragmentSurface& s, const std::function<uint32_t(const ShapeTables&)>& count,
                      const std::function<uint32_t(const ShapeTables&, uint32_t)>& kind_of, uint32_t any_key) {
  std::vector<uint64_t> fragments_of(s.tables.size(), 0);
  for (const auto& f : s.partition.fragments) ++fragments_of[f.shape];
  std::vector<std::vector<uint32_t>> kinds_of(s.tables.size());
  std::map<uint32_t, uint64_t> weight;
  uint64_t total = 0;
  for (size_t shape = 0; shape < s.tables.size(); ++shape)
    for (uint32_t i = 0; i < count(s.tables[shape]); ++i) {
      kinds_of[shape].push_back(kind_of(s.tables[shape], i));
      weight[kinds_of[shape].back()] += fragments_of[shape];
      total += fragments_of[shape];
    }
  std::vector<std::pair<uint64_t, uint32_t>> by_weight;
  for (const auto& [key, w] : weight) by_weight.emplace_back(w, key);
  std::sort(by_weight.rbegin(), by_weight.rend());
  EntryKinds kinds;
  for (const auto& [w, key] : by_weight)
    if (kinds.keys.size() < kMaxKinds && w >= kMinKindShare * double(total)) kinds.keys.push_back(key);
  if (kinds.keys.size() < by_weight.size()) kinds.keys.push_back(any_key);
  kinds.lists.assign(kinds.keys.size(), std::vector<std::vector<uint32_t>>(s.tables.size()));
  for (size_t shape = 0; shape < s.tables.size(); ++shape)
    for (uint32_t i = 0; i < kinds_of[shape].size(); ++i) {
      const auto it = std::find(kinds.keys.begin(), kinds.keys.end(), kinds_of[shape][i]);
      kinds.lists[it == kinds.keys.end() ? kinds.keys.size() - 1 : size_t(it - kinds.keys.begin())][shape].push_back(i);
    }
  return kinds;
}

// Loop iterations (shaders/fragments.glsl) of a ring sum and of a rule, bounded from above.
uint64_t ring_cost(uint32_t n) {
  if (n == 1 || n == 2 || n == 4 || n == 6 || n == 8) return 0;
  return 3 * (uint64_t(n) * (2 * n + 2) + 1);
}
uint64_t vertex_rule_cost(const VertexRule& r) { return 1 + ring_cost(r.num_e) + ring_cost(r.num_f); }

uint64_t limit_cost(const LimitTable& lim, uint32_t i) {
  uint64_t cost = 1 + (lim.stencil[i] < 0 ? vertex_rule_cost(lim.position[i])
                                          : lim.stencil_begin[lim.stencil[i] + 1] - lim.stencil_begin[lim.stencil[i]]);
  if (lim.net_size) cost += lim.net_size;
  else if (lim.regular[i] < 0) cost += lim.tangent_begin[i + 1] - lim.tangent_begin[i];
  return cost;
}

uint64_t worst_chunk(const std::vector<uint64_t>& costs, uint32_t chunk) {
  uint64_t worst = 0;
  for (size_t i = 0; i < costs.size(); i += chunk) {
    uint64_t sum = 0;
    for (size_t k = i; k < std::min(costs.size(), i + chunk); ++k) sum += costs[k];
    worst = std::max(worst, sum);
  }
  return worst;
}

class Planner {
 public:
  Planner(const FragmentSurface& s, DeviceTables& tables, bool loop_limited, const std::string& device)
      : s_(s), tables_(tables), loop_limited_(loop_limited), device_(device) {}

  // A pass over entries [0, count(shape)) of every shape, each costing cost(shape, entry).
  void add(PassSpec p, const std::function<uint32_t(const ShapeTables&)>& count,
           const std::function<uint64_t(const ShapeTables&, uint32_t)>& cost) {
    std::vector<std::vector<uint64_t>> costs;
    for (const ShapeTables& t : s_.tables) {
      costs.emplace_back();
      for (uint32_t i = 0; i < count(t); ++i) costs.back().push_back(cost(t, i));
    }
    finish(std::move(p), costs);
  }

  // A pass per kind, over that kind's entries.
  void add_kinds(PassSpec p, const EntryKinds& kinds, const std::function<uint64_t(const ShapeTables&, uint32_t)>& cost) {
    const uint32_t pairs = append_kind_lists(tables_, kinds.lists);
    for (size_t k = 0; k < kinds.keys.size(); ++k) {
      PassSpec q = p;
      q.key = kinds.keys[k];
      q.kind_pairs = pairs + static_cast<uint32_t>(2 * k * s_.tables.size());
      std::vector<std::vector<uint64_t>> costs;
      for (size_t shape = 0; shape < s_.tables.size(); ++shape) {
        costs.emplace_back();
        for (uint32_t i : kinds.lists[k][shape]) costs.back().push_back(cost(s_.tables[shape], i));
      }
      finish(std::move(q), costs);
    }
  }

  std::vector<PassSpec> passes;

 private:
  void finish(PassSpec p, const std::vector<std::vector<uint64_t>>& costs) {
    auto fits = [&](uint32_t chunk) {
      return std::all_of(costs.begin(), costs.end(), [&](const auto& c) { return worst_chunk(c, chunk) <= kLoopBudget; });
    };
    while (p.chunk > 1 && !fits(p.chunk)) p.chunk /= 2;
    for (const std::vector<uint64_t>& c : costs) {
      p.chunk_costs.emplace_back();
      for (size_t i = 0; i < c.size(); i += p.chunk)
        p.chunk_costs.back().push_back(
            std::accumulate(c.begin() + i, c.begin() + std::min(c.size(), i + p.chunk), uint64_t(0)));
    }
    if (loop_limited_ && !fits(p.chunk))
      throw gpu::Unsupported(device_ + " stops every shader invocation after 65,535 loop iterations; a fragment's " +
                             (p.part == Part::Limit ? std::string("limit") : "level " + std::to_string(p.level)) +
                             " entry here needs more (a vertex of high valence)");
    passes.push_back(std::move(p));
  }

  const FragmentSurface& s_;
  DeviceTables& tables_;
  bool loop_limited_;
  const std::string& device_;
};

}  // namespace

std::vector<PassSpec> plan_passes(const FragmentSurface& s, DeviceTables& tables, bool project, bool loop_limited,
                                  const std::string& device) {
  Planner plan(s, tables, loop_limited, device);
  auto one = [](const ShapeTables&, uint32_t) { return uint64_t(1); };
  plan.add({Part::Gather}, [](const ShapeTables& t) { return t.num_slots0; }, one);
  for (uint32_t d = 1; d <= static_cast<uint32_t>(s.inner_depth); ++d) {
    auto level = [d](const ShapeTables& t) -> const LevelTable& { return t.levels[d - 1]; };
    if (s.rule == SubdivisionRule::CatmullClark)
      plan.add({Part::Faces, d}, [&](const ShapeTables& t) { return uint32_t(level(t).faces.size()); }, one);
    plan.add({Part::Edges, d}, [&](const ShapeTables& t) { return uint32_t(level(t).edges.size()); }, one);
    auto vertices = [&](const ShapeTables& t) { return uint32_t(level(t).vertices.size()); };
    const EntryKinds kinds = plan_kinds(
        s, vertices, [&](const ShapeTables& t, uint32_t i) { return rule_kind(level(t).vertices[i]); }, kRuleAny);
    plan.add_kinds({Part::Vertices, d}, kinds,
                   [&](const ShapeTables& t, uint32_t i) { return vertex_rule_cost(level(t).vertices[i]); });
  }
  const EntryKinds kinds = plan_kinds(
      s, [](const ShapeTables& t) { return uint32_t(t.block_vertices()); },
      [project](const ShapeTables& t, uint32_t i) { return limit_kind(t, i, project); }, kLimitAny);
  plan.add_kinds({Part::Limit}, kinds, [](const ShapeTables& t, uint32_t i) { return limit_cost(t.limit, i); });
  for (const bool triangle : {false, true}) {
    auto patch = [triangle](const ShapeTables& t) {
      return !t.limit.patch_weights.empty() && t.limit.patch_triangle == triangle;
    };
    if (std::none_of(s.tables.begin(), s.tables.end(), patch)) continue;
    // Entries are rows; each chunk also sums the coefficients over the net.
    plan.add({Part::Patch, 0, triangle ? 1u : 0u},
             [&](const ShapeTables& t) { return patch(t) ? uint32_t(t.limit.patch_segments + 1) : 0u; },
             [](const ShapeTables& t, uint32_t) { return uint64_t(t.limit.patch_segments + 1) + t.limit.net_size; });
  }
  return std::move(plan.passes);
}

std::vector<WorkItem> interleave_by_cost(const std::vector<WorkItem>& items) {
  std::map<uint32_t, std::vector<WorkItem>> by_batch;
  for (const WorkItem& item : items) by_batch[item.batch].push_back(item);
  std::vector<std::pair<uint64_t, const std::vector<WorkItem>*>> batches;
  for (const auto& [batch, its] : by_batch) {
    uint64_t cost = 0;
    for (const WorkItem& item : its) cost += item.cost;
    batches.emplace_back(cost, &its);
  }
  std::stable_sort(batches.begin(), batches.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  uint32_t bits = 0;
  while ((size_t(1) << bits) < batches.size()) ++bits;
  std::vector<WorkItem> out;
  out.reserve(items.size());
  for (size_t p = 0; p < (size_t(1) << bits); ++p) {
    size_t r = 0;
    for (uint32_t b = 0; b < bits; ++b) r |= ((p >> b) & 1) << (bits - 1 - b);
    if (r < batches.size()) out.insert(out.end(), batches[r].second->begin(), batches[r].second->end());
  }
  return out;
}

std::string pass_label(const PassSpec& pass) {
  if (pass.part == Part::Gather) return "gather";
  if (pass.part == Part::Limit || pass.part == Part::Patch) return "limit";
  return "level " + std::to_string(pass.level);
}

}  // namespace sdb::fragments
