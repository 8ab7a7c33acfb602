#include "harness/run/plan.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <regex>
#include <set>

#include "datasets/manifest.h"
#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/gl/context.h"
#include "harness/gpu/device_info.h"
#include "harness/results/statistics.h"

namespace sdb {
namespace {

bool contains(const std::vector<RunSpec>& runs, const RunSpec& r) {
  return std::any_of(runs.begin(), runs.end(), [&](const RunSpec& x) { return x.name() == r.name(); });
}

// Every scheme's headline runs, each after its peer's run at the same mesh, backend and
// tessellation: the figures a README quotes come with the peer they are quoted against.
std::vector<RunSpec> headline_runs() {
  std::vector<RunSpec> runs;
  for (const auto& s : all_schemes()) {
    const SchemeInfo& info = s->info();
    for (const HeadlineRun& h : info.headline_runs) {
      if (const Scheme* peer = info.peer.empty() ? nullptr : find_scheme(info.peer)) {
        const auto backend = peer_backend_for(info, h.backend);
        const auto level = level_for_segments(peer->info().level_kind, segments_per_edge(info.level_kind, h.level));
        if (backend && level) runs.push_back({info.peer, h.mesh, *backend, *level});
      }
      runs.push_back({info.name, h.mesh, h.backend, h.level});
    }
  }
  return runs;
}

// Every level the scheme takes on `accepted` and backend `b` (those its unsupported() does not
// decline, depths 0..kDeepestDepth, rates 2..kFinestRate), with its predicted output in triangles.
std::vector<std::pair<int, long>> supported_levels(const ResolvedScheme& r, const ControlMesh& accepted, Backend b) {
  const SchemeInfo& info = r.scheme->info();
  const auto [first, last] = info.level_kind == LevelKind::Depth ? std::pair{0, kDeepestDepth} : std::pair{2, kFinestRate};
  std::vector<std::pair<int, long>> levels;
  for (int level = first; level <= last; ++level) {
    const RunRequest request{b, level, 0, r.parameters};
    if (!r.scheme->unsupported(request)) levels.emplace_back(level, r.scheme->estimated_triangles(accepted, request));
  }
  return levels;
}

// The levels a run of `r` on `accepted` and backend `b` takes: the selection's; else the level whose
// predicted output is nearest the summary's size (kSummaryTriangles: the cell the report and the
// paired rounds read), and beside it the quick set's smaller level (quick_levels) or the default
// set's default levels within the output budget. A scheme that declines every level (a device it
// lacks) keeps its default levels: their rows say why.
std::vector<int> levels_for(const Selection& sel, const ResolvedScheme& r, const ControlMesh& accepted, Backend b) {
  if (!sel.levels.empty()) return sel.levels;
  const std::vector<std::pair<int, long>> supported = supported_levels(r, accepted, b);
  if (supported.empty()) return r.scheme->info().default_levels;
  if (sel.quick) return quick_levels(supported);
  std::vector<int> levels = {nearest_level(supported, kSummaryTriangles)->first};
  for (int level : r.scheme->info().default_levels) {
    const long triangles = r.scheme->estimated_triangles(accepted, {b, level, 0, r.parameters});
    if (triangles <= sel.max_triangles && std::find(levels.begin(), levels.end(), level) == levels.end())
      levels.push_back(level);
  }
  std::sort(levels.begin(), levels.end());
  return levels;
}

// Whether one of `levels` gives an output within the summary's band (kSummaryLow..kSummaryHigh).
bool reaches_summary_size(const ResolvedScheme& r, const ControlMesh& accepted, Backend b, const std::vector<int>& levels) {
  return std::any_of(levels.begin(), levels.end(), [&](int level) {
    const long triangles = r.scheme->estimated_triangles(accepted, {b, level, 0, r.parameters});
    return triangles >= kSummaryLow && triangles <= kSummaryHigh;
  });
}

// For each scheme, mesh and backend of `runs` none of whose levels is within the summary's band (a
// headline run alone on its mesh: the sword's 45.8 M triangles), the level nearest
// kSummaryTriangles too, so that every summary cell is read at a size that means the same.
void add_summary_levels(std::vector<RunSpec>& runs, MeasureContext& ctx) {
  std::map<std::string, std::vector<int>> levels;  // spec|mesh|backend
  std::vector<RunSpec> cells;
  for (const RunSpec& r : runs) {
    auto [it, fresh] = levels.emplace(r.scheme + "|" + r.mesh + "|" + std::string(to_string(r.backend)), std::vector<int>{});
    if (fresh) cells.push_back(r);
    it->second.push_back(r.level);
  }
  for (const RunSpec& c : cells) {
    const ResolvedScheme r = resolve_scheme(c.scheme);
    std::shared_ptr<const ControlMesh> accepted;
    try {
      accepted = ctx.accepted(c.mesh, *r.scheme);
    } catch (const InputError&) {
      continue;  // refused: its rows say so
    }
    if (reaches_summary_size(r, *accepted, c.backend, levels[c.scheme + "|" + c.mesh + "|" + std::string(to_string(c.backend))]))
      continue;
    const std::vector<std::pair<int, long>> supported = supported_levels(r, *accepted, c.backend);
    if (supported.empty()) continue;
    const auto nearest = nearest_level(supported, kSummaryTriangles);
    runs.push_back({c.scheme, c.mesh, c.backend, nearest->first});
    if (nearest->second >= kSummaryLow && nearest->second <= kSummaryHigh) continue;
    // Its levels cannot reach the band on this mesh (osd-bfr's N <= 129 on the 6-quad creased
    // cube): the mesh's rows stay for what they validate, and the scheme's rule's larger built-in
    // gives its speed a cell at the summary's size.
    try {
      const std::string larger = quick_fallback_mesh(r.scheme->info().reference);
      const auto on_larger = supported_levels(r, *ctx.accepted(larger, *r.scheme), c.backend);
      if (!on_larger.empty()) runs.push_back({c.scheme, larger, c.backend, nearest_level(on_larger, kSummaryTriangles)->first});
    } catch (const InputError&) {
    }
  }
}

// The meshes a scheme runs on: the selection's, the quick set's of its rule, or the default set.
std::vector<std::string> meshes_for(const Selection& sel, const SchemeInfo& info) {
  if (!sel.meshes.empty()) return sel.meshes;
  if (!sel.quick) return default_meshes(sel.all_meshes, sel.all_corpus);
  std::vector<std::string> meshes;
  for (const QuickMesh& m : quick_meshes())
    if (m.rule == info.reference) meshes.push_back(m.name);
  return meshes;
}

}  // namespace

std::vector<std::pair<int, long>>::const_iterator nearest_level(const std::vector<std::pair<int, long>>& level_triangles,
                                                                long target) {
  return std::min_element(level_triangles.begin(), level_triangles.end(), [&](const auto& a, const auto& b) {
    return log_distance(a.second, target) < log_distance(b.second, target);
  });
}

std::vector<int> quick_levels(const std::vector<std::pair<int, long>>& level_triangles) {
  std::vector<std::pair<int, long>> left = level_triangles;
  std::vector<int> chosen;
  // The summary cell: the smallest output within the band (validating a cell costs about 3 us of
  // CPU per triangle, and the quick set has some 50 of them), else the one nearest the band's middle.
  auto summary = left.cend();
  for (auto it = left.cbegin(); it != left.cend(); ++it)
    if (it->second >= kSummaryLow && it->second <= kSummaryHigh && (summary == left.cend() || it->second < summary->second))
      summary = it;
  if (summary == left.cend()) summary = nearest_level(left, kSummaryTriangles);
  if (summary != left.cend()) {
    chosen.push_back(summary->first);
    left.erase(summary);
  }
  if (!left.empty()) {
    const auto low = nearest_level(left, kQuickLow);
    chosen.push_back(low->first);
  }
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

std::string quick_fallback_mesh(SubdivisionRule rule) {
  return rule == SubdivisionRule::Loop ? "icosphere-5" : "frog-party";
}

std::vector<QuickMesh> quick_meshes() {
  // The corpus's Spot: a real quad mesh, 81% of its quads extraordinary; without the corpus, the
  // Sword stand-in (random quads, 38% extraordinary) in its place. One mesh per rule: at 0.5-2 M
  // triangles a cell's validation costs seconds, and the quad sphere's cells doubled the run for
  // a mesh with eight extraordinary vertices.
  const std::string real = corpus_dir() ? "crane/spot_control" : "sword-standin";
  return {{"icosphere", SubdivisionRule::Loop}, {real, SubdivisionRule::CatmullClark}};
}

std::vector<RunSpec> distinct_runs(const std::vector<RunSpec>& runs, std::vector<std::string>* notes) {
  std::set<std::string> seen;
  std::vector<RunSpec> once;
  for (const RunSpec& r : runs) {
    if (seen.insert(r.name()).second) once.push_back(r);
    else if (notes) notes->push_back(r.name() + " is named more than once: measured once");
  }
  return once;
}

std::pair<int, int> parse_shard(const std::string& text) {
  static const std::regex form(R"((\d{1,6})/(\d{1,6}))");
  std::smatch m;
  if (!std::regex_match(text, m, form)) throw InputError("--shard " + text, "expected I/N, e.g. 0/4 (I counts from 0)");
  const int index = std::stoi(m[1]), count = std::stoi(m[2]);
  if (count < 1 || index >= count) throw InputError("--shard " + text, "needs 0 <= I < N");
  return {index, count};
}

std::vector<RunSpec> shard_runs(const std::vector<RunSpec>& runs, int index, int count) {
  std::vector<std::string> names;
  for (const RunSpec& r : runs) names.push_back(r.name());
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  std::vector<RunSpec> kept;
  for (const RunSpec& r : runs) {
    const auto position = std::lower_bound(names.begin(), names.end(), r.name()) - names.begin();
    if (position % count == index) kept.push_back(r);
  }
  return kept;
}

MeasureOptions measure_options(const RunSelection& r) {
  MeasureOptions m;
  m.reps = r.reps;
  m.rays = r.rays;
  m.seed = r.seed;
  m.validate = r.validate;
  // The quick set: a first look in minutes. Its rows are single-pass figures either way (the
  // paired rounds give the ratios), so shorter repetitions lose little.
  m.hausdorff_only_without_coords = r.selection.quick;
  if (r.selection.quick) m.min_time_s = kQuickMinTime;
  m.refusals_as_rows = !(r.selection.schemes.size() == 1 && r.selection.meshes.size() == 1);
  return m;
}

std::vector<Backend> available_backends() {
  std::vector<Backend> b = {Backend::Cpu, Backend::CpuMt};
  if (gpu::probe().available) b.push_back(Backend::Vulkan);
  if (gl::probe().available) b.push_back(Backend::OpenGl);
  return b;
}

std::vector<std::string> default_meshes(bool all, bool all_corpus) {
  std::set<std::string> curated;
  for (const auto& s : all_schemes()) curated.insert(s->info().default_meshes.begin(), s->info().default_meshes.end());
  std::vector<std::string> out;
  for (const auto& e : list_meshes()) {
    const bool osd_shape = e.name.rfind("opensubdiv/", 0) == 0;
    const bool take = all ? (e.kind == "builtin" || all_corpus || !osd_shape) : curated.count(e.name) > 0;
    if (take) out.push_back(e.name);
  }
  return out;
}

Plan make_plan(const Selection& sel, MeasureContext& ctx) {
  Plan plan;
  std::vector<ResolvedScheme> schemes;
  if (sel.schemes.empty()) {
    for (const auto& s : all_schemes())
      if (s->info().role != SchemeRole::Test) schemes.push_back(resolve_scheme(s->info().name));
  } else {
    for (const auto& spelled : sel.schemes) schemes.push_back(resolve_scheme(spelled));
  }
  std::vector<Backend> backends;
  for (const auto& b : sel.backends) {
    auto parsed = parse_backend(b);
    if (!parsed) throw InputError(b, "no such backend (" + backend_names() + ")");
    backends.push_back(*parsed);
  }
  const std::vector<Backend> available = available_backends();
  const bool explicit_pair = sel.schemes.size() == 1 && sel.meshes.size() == 1;
  for (const ResolvedScheme& r : schemes) {
    const SchemeInfo& info = r.scheme->info();
    for (const auto& mesh : meshes_for(sel, info)) {
      std::shared_ptr<const ControlMesh> accepted;
      try {
        accepted = ctx.accepted(mesh, *r.scheme);
      } catch (const InputError& e) {
        if (explicit_pair) throw;
        if (!sel.meshes.empty()) plan.notes.push_back("skipped " + r.spec + " on " + mesh + ": " + e.what());
        continue;
      }
      for (Backend b : info.backends) {
        if (!backends.empty() && std::find(backends.begin(), backends.end(), b) == backends.end()) continue;
        if (std::find(available.begin(), available.end(), b) == available.end()) {
          plan.notes.push_back("skipped " + r.spec + " on " + std::string(to_string(b)) + ": backend unavailable");
          continue;
        }
        std::string on = mesh;
        std::vector<int> levels = levels_for(sel, r, *accepted, b);
        if (sel.quick && !reaches_summary_size(r, *accepted, b, levels)) {
          // The quick mesh is too small for this scheme's levels: its rule's larger built-in instead.
          // A scheme that refuses that one too keeps its quick mesh, and its summary cell says its size.
          try {
            const std::string larger = quick_fallback_mesh(info.reference);
            levels = levels_for(sel, r, *ctx.accepted(larger, *r.scheme), b);
            on = larger;
          } catch (const InputError&) {
          }
        }
        for (int level : levels) plan.runs.push_back({r.spec, on, b, level});
      }
    }
  }
  if (sel.headline && !sel.quick && sel.schemes.empty() && sel.meshes.empty() && sel.levels.empty())
    for (const RunSpec& h : headline_runs())
      if (!contains(plan.runs, h)) {
        try {
          ctx.accepted(h.mesh, *find_scheme(h.scheme));
          plan.runs.push_back(h);
        } catch (const InputError&) {
          // the mesh is absent (the corpus is not beside the checkout): no headline figure
        }
      }
  if (sel.levels.empty()) add_summary_levels(plan.runs, ctx);
  plan.runs = distinct_runs(plan.runs, &plan.notes);
  if (sel.shard_count > 1) {
    const size_t all = plan.runs.size();
    plan.runs = shard_runs(plan.runs, sel.shard_index, sel.shard_count);
    plan.notes.push_back("shard " + std::to_string(sel.shard_index) + "/" + std::to_string(sel.shard_count) + ": " +
                         std::to_string(plan.runs.size()) + " of the selection's " + std::to_string(all) + " runs");
  }
  return plan;
}

}  // namespace sdb
