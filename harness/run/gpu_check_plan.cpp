#include "harness/run/gpu_check_plan.h"

#include <algorithm>
#include <cmath>

#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/results/statistics.h"

namespace sdb {
namespace {

// The entry of `levels` whose output is nearest `target`, among those `keep` takes.
template <typename Keep>
std::optional<std::pair<int, long>> nearest(const std::vector<std::pair<int, long>>& levels, double target, Keep keep) {
  std::optional<std::pair<int, long>> best;
  for (const auto& lt : levels)
    if (keep(lt) && (!best || log_distance(double(lt.second), target) < log_distance(double(best->second), target))) best = lt;
  return best;
}

// The levels of `scheme` on `backend` that it does not decline, with their estimated outputs,
// ascending, up to the first past `max` (beyond it nothing is chosen).
std::vector<std::pair<int, long>> supported_levels(const Scheme& scheme, const ControlMesh& accepted, Backend backend,
                                                   long max) {
  const SchemeInfo& info = scheme.info();
  const bool depth = info.level_kind == LevelKind::Depth;
  std::vector<std::pair<int, long>> levels;
  for (int level = depth ? 0 : 2; level <= (depth ? 16 : 1025); ++level) {
    const RunRequest request = default_request(info, backend, level);
    if (declined(scheme, request)) continue;
    const long triangles = scheme.estimated_triangles(accepted, request);
    if (triangles <= 0) continue;
    levels.emplace_back(level, triangles);
    if (triangles > max) break;
  }
  return levels;
}

bool any_within(const std::vector<std::pair<int, long>>& levels, const OutputBounds& b) {
  return std::any_of(levels.begin(), levels.end(), [&](const auto& lt) { return lt.second >= b.min && lt.second <= b.max; });
}

struct MeshChoice {
  std::string mesh;
  std::vector<std::pair<int, long>> levels;
};

// The first candidate the scheme accepts on which a level gives an output within the bounds; else
// the first it accepts at all.
std::optional<MeshChoice> choose_mesh(const Scheme& scheme, Backend backend, const OutputBounds& bounds, bool quick,
                                      MeasureContext& context) {
  std::optional<MeshChoice> fallback;
  for (const std::string& mesh : check_mesh_candidates(scheme.info(), quick)) {
    std::shared_ptr<const ControlMesh> accepted;
    try {
      accepted = context.accepted(mesh, scheme);
    } catch (const InputError&) {
      continue;  // refused, or absent (the corpus is not here)
    }
    MeshChoice choice{mesh, supported_levels(scheme, *accepted, backend, bounds.max)};
    if (choice.levels.empty()) continue;
    if (any_within(choice.levels, bounds)) return choice;
    if (!fallback) fallback = std::move(choice);
  }
  return fallback;
}

// The CPU row beside a GPU row: the scheme's own cpu-mt row at the same level, else its peer's row
// on the peer's backend at the same segments per edge; none where the peer refuses the mesh.
std::optional<RunSpec> cpu_row(const SchemeInfo& info, const std::string& mesh, int level, Backend gpu_backend,
                               MeasureContext& context) {
  if (std::find(info.backends.begin(), info.backends.end(), Backend::CpuMt) != info.backends.end())
    return RunSpec{info.name, mesh, Backend::CpuMt, level};
  const Scheme* peer = info.peer.empty() ? nullptr : find_scheme(info.peer);
  const auto backend = peer_backend_for(info, gpu_backend);
  if (!peer || !backend || is_gpu(*backend)) return std::nullopt;
  const auto peer_level = level_for_segments(peer->info().level_kind, segments_per_edge(info.level_kind, level));
  if (!peer_level) return std::nullopt;
  try {
    context.accepted(mesh, *peer);
  } catch (const InputError&) {
    return std::nullopt;
  }
  return RunSpec{info.peer, mesh, *backend, *peer_level};
}

std::string level_words(const SchemeInfo& info, int level) {
  return (info.level_kind == LevelKind::Depth ? "depth " : "N = ") + std::to_string(level);
}

}  // namespace

std::string CheckGroup::name() const { return "size " + std::to_string(size) + ": " + scheme; }
std::string CheckGroup::slug() const { return std::to_string(size) + "-" + scheme; }

std::vector<int> check_levels(const std::vector<std::pair<int, long>>& levels, const OutputBounds& b) {
  auto first = nearest(levels, double(b.target), [&](const auto& lt) { return lt.second >= b.min && lt.second <= b.max; });
  if (!first) first = nearest(levels, double(b.target), [](const auto&) { return true; });
  if (!first) return {};
  const long t = first->second;
  auto second = nearest(levels, 4.0 * double(t), [&](const auto& lt) { return lt.second > t && lt.second <= b.max; });
  if (!second) second = nearest(levels, double(t) / 4, [&](const auto& lt) { return lt.second < t; });
  if (!second) return {first->first};
  return {first->first, second->first};
}

std::vector<std::string> check_mesh_candidates(const SchemeInfo& info, bool quick) {
  std::vector<std::string> large = info.large_meshes;
  if (large.empty())
    for (const HeadlineRun& h : info.headline_runs) large.push_back(h.mesh);
  std::vector<std::string> ordered;
  if (quick) ordered = info.default_meshes;
  ordered.insert(ordered.end(), large.begin(), large.end());
  if (!quick) ordered.insert(ordered.end(), info.default_meshes.begin(), info.default_meshes.end());
  std::vector<std::string> unique;
  for (const std::string& m : ordered)
    if (std::find(unique.begin(), unique.end(), m) == unique.end()) unique.push_back(m);
  return unique;
}

CheckPlan plan_gpu_check(const OutputBounds& bounds, bool quick, const std::vector<Backend>& gpu_backends,
                         MeasureContext& context) {
  CheckPlan plan;
  std::vector<CheckGroup> second;
  for (const auto& s : all_schemes()) {
    const SchemeInfo& info = s->info();
    if (info.role == SchemeRole::Test) continue;
    std::vector<Backend> backends;
    for (Backend b : info.backends)
      if (is_gpu(b)) backends.push_back(b);
    if (backends.empty()) continue;  // a CPU scheme: its rows are the CPU rows beside the others
    std::vector<Backend> usable;
    for (Backend b : backends)
      if (std::find(gpu_backends.begin(), gpu_backends.end(), b) != gpu_backends.end()) usable.push_back(b);
    if (usable.empty()) {
      plan.notes.push_back(info.name + ": left out, its backend (" + std::string(to_string(backends.front())) +
                           ") is unavailable here");
      continue;
    }
    const std::optional<MeshChoice> choice = choose_mesh(*s, usable.front(), bounds, quick, context);
    if (!choice) {
      plan.notes.push_back(info.name + ": left out, it takes none of its meshes here (" +
                           std::to_string(check_mesh_candidates(info, quick).size()) + " tried)");
      continue;
    }
    const std::vector<int> levels = check_levels(choice->levels, bounds);
    for (size_t k = 0; k < levels.size(); ++k) {
      CheckGroup g;
      g.size = int(k) + 1;
      g.scheme = info.name, g.mesh = choice->mesh, g.level = levels[k];
      for (const auto& [level, triangles] : choice->levels)
        if (level == g.level) g.triangles = triangles;
      for (Backend b : usable) g.runs.push_back({info.name, g.mesh, b, g.level});
      if (auto cpu = cpu_row(info, g.mesh, g.level, usable.front(), context)) g.runs.push_back(*cpu);
      (k == 0 ? plan.groups : second).push_back(std::move(g));
    }
    if (levels.size() < 2)
      plan.notes.push_back(info.name + ": one size only, " + level_words(info, levels.at(0)) + " on " + choice->mesh +
                           " (no second level it takes)");
  }
  plan.groups.insert(plan.groups.end(), second.begin(), second.end());
  // Within a size the paper methods before the peers: the peers' tables take the longest to make
  // (OpenSubdiv's limit stencils), and a budget spent early should cost a peer's figure first.
  std::stable_sort(plan.groups.begin(), plan.groups.end(), [](const CheckGroup& a, const CheckGroup& b) {
    auto role = [](const CheckGroup& g) { return find_scheme(g.scheme)->info().role == SchemeRole::Method ? 0 : 1; };
    return std::make_pair(a.size, role(a)) < std::make_pair(b.size, role(b));
  });
  return plan;
}

}  // namespace sdb
