#include "plan.h"

#include <algorithm>

#include "device_info.h"
#include "errors.h"
#include "facts.h"
#include "manifest.h"
#include "registry.h"

namespace sdb {
namespace {

// Benchmark figures the project reports (README, notes): in the default set whatever the budget.
const std::vector<RunSpec>& headline_runs() {
  static const std::vector<RunSpec> runs = {
      {"osd-bfr", "stein/sword_quad_dominant", Backend::Cpu, 9},
      {"cpatch-2pass", "stein/sword_quad_dominant", Backend::Cpu, 9},
      {"cpatch-2pass", "stein/sword_quad_dominant", Backend::CpuMt, 9},
      {"osd-bfr", "stein/sword_quad_dominant", Backend::CpuMt, 9},
  };
  return runs;
}

bool contains(const std::vector<RunSpec>& runs, const RunSpec& r) {
  return std::any_of(runs.begin(), runs.end(), [&](const RunSpec& x) { return x.name() == r.name(); });
}

}  // namespace

std::vector<Backend> available_backends() {
  std::vector<Backend> b = {Backend::Cpu, Backend::CpuMt};
  if (gpu::probe().available) b.push_back(Backend::Vulkan);
  return b;
}

std::vector<std::string> default_meshes(bool all, bool all_corpus) {
  static const std::vector<std::string> curated = {
      "torus",          "quadsphere",         "pole3",       "pole8",        "icosphere",
      "creased-cube",   "sword-standin",      "head-standin", "frog-standin", "gim-sphere-31",
      "crane/spot_control", "crane/blub_control", "pmp/fandisk_quads", "stanford/bunny"};
  std::vector<std::string> out;
  for (const auto& e : list_meshes()) {
    const bool osd_shape = e.name.rfind("opensubdiv/", 0) == 0;
    const bool take = all ? (e.kind == "builtin" || all_corpus || !osd_shape)
                          : std::find(curated.begin(), curated.end(), e.name) != curated.end();
    if (take) out.push_back(e.name);
  }
  return out;
}

Plan make_plan(const Selection& sel, MeasureContext& ctx) {
  Plan plan;
  std::vector<const Scheme*> schemes;
  if (sel.schemes.empty()) {
    for (const auto& s : all_schemes()) schemes.push_back(s.get());
  } else {
    for (const auto& name : sel.schemes) {
      const Scheme* s = find_scheme(name);
      if (!s) throw InputError(name, "no such scheme (see `subdivbench list schemes`)");
      schemes.push_back(s);
    }
  }
  std::vector<Backend> backends;
  for (const auto& b : sel.backends) {
    auto parsed = parse_backend(b);
    if (!parsed) throw InputError(b, "no such backend (cpu, cpu-mt, vulkan)");
    backends.push_back(*parsed);
  }
  const std::vector<Backend> available = available_backends();
  const bool explicit_pair = sel.schemes.size() == 1 && sel.meshes.size() == 1;
  const std::vector<std::string> meshes = sel.meshes.empty() ? default_meshes(sel.all_meshes, sel.all_corpus) : sel.meshes;
  for (const Scheme* s : schemes) {
    const SchemeInfo& info = s->info();
    for (const auto& mesh : meshes) {
      std::shared_ptr<const ControlMesh> accepted;
      try {
        accepted = ctx.accepted(mesh, *s);
      } catch (const InputError& e) {
        if (explicit_pair) throw;
        if (!sel.meshes.empty()) plan.notes.push_back("skipped " + info.name + " on " + mesh + ": " + e.what());
        continue;
      }
      for (Backend b : info.backends) {
        if (!backends.empty() && std::find(backends.begin(), backends.end(), b) == backends.end()) continue;
        if (std::find(available.begin(), available.end(), b) == available.end()) {
          plan.notes.push_back("skipped " + info.name + " on " + std::string(to_string(b)) + ": backend unavailable");
          continue;
        }
        for (int level : sel.levels.empty() ? info.default_levels : sel.levels) {
          if (sel.levels.empty() && s->estimated_triangles(*accepted, {b, level, 0}) > sel.max_triangles) continue;
          plan.runs.push_back({info.name, mesh, b, level});
        }
      }
    }
  }
  if (sel.headline && sel.schemes.empty() && sel.meshes.empty() && sel.levels.empty())
    for (const RunSpec& r : headline_runs())
      if (find_scheme(r.scheme) && !contains(plan.runs, r)) {
        try {
          ctx.accepted(r.mesh, *find_scheme(r.scheme));
          plan.runs.push_back(r);
        } catch (const InputError&) {
          // the corpus is absent: the headline runs need the sword
        }
      }
  return plan;
}

}  // namespace sdb
