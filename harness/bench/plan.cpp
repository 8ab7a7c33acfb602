#include "harness/bench/plan.h"

#include <algorithm>
#include <set>

#include "datasets/manifest.h"
#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/gl/context.h"
#include "harness/gpu/device_info.h"

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

}  // namespace

MeasureOptions measure_options(const RunSelection& r) {
  MeasureOptions m;
  m.reps = r.reps;
  m.rays = r.rays;
  m.seed = r.seed;
  m.validate = r.validate;
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
  const std::vector<std::string> meshes = sel.meshes.empty() ? default_meshes(sel.all_meshes, sel.all_corpus) : sel.meshes;
  for (const ResolvedScheme& r : schemes) {
    const SchemeInfo& info = r.scheme->info();
    for (const auto& mesh : meshes) {
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
        for (int level : sel.levels.empty() ? info.default_levels : sel.levels) {
          if (sel.levels.empty() && r.scheme->estimated_triangles(*accepted, {b, level, 0, r.parameters}) > sel.max_triangles)
            continue;
          plan.runs.push_back({r.spec, mesh, b, level});
        }
      }
    }
  }
  if (sel.headline && sel.schemes.empty() && sel.meshes.empty() && sel.levels.empty())
    for (const RunSpec& h : headline_runs())
      if (!contains(plan.runs, h)) {
        try {
          ctx.accepted(h.mesh, *find_scheme(h.scheme));
          plan.runs.push_back(h);
        } catch (const InputError&) {
          // the mesh is absent (the corpus is not beside the checkout): no headline figure
        }
      }
  return plan;
}

}  // namespace sdb
