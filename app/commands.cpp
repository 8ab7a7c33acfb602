#include "app/commands.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <thread>

#include "datasets/manifest.h"
#include "harness/core/errors.h"
#include "harness/core/printable.h"
#include "harness/core/registry.h"
#include "harness/gl/context.h"
#include "harness/gpu/device_info.h"
#include "harness/mesh/facts.h"

namespace sdb::app {
namespace {

struct MeshVerbOptions {
  std::string list_what = "schemes";
  std::string mesh;
  bool json = false;
};

nlohmann::json facts_json(const ControlMesh& m, const MeshFacts& f) {
  auto hist = [](const std::map<int, int>& h) {
    nlohmann::json j = nlohmann::json::object();
    for (auto [k, v] : h) j[std::to_string(k)] = v;
    return j;
  };
  return {{"name", m.name},
          {"source", m.source},
          {"vertices", f.vertices},
          {"faces", f.faces},
          {"edges", f.edges},
          {"face_sizes", hist(f.face_sizes)},
          {"valences", hist(f.valences)},
          {"boundary_edges", f.boundary_edges},
          {"boundary_loops", f.boundary_loops},
          {"non_manifold_edges", f.non_manifold_edges},
          {"non_manifold_vertices", f.non_manifold_vertices},
          {"inconsistent_edges", f.inconsistent_edges},
          {"degenerate_faces", f.degenerate_faces},
          {"unused_vertices", f.unused_vertices},
          {"components", f.components},
          {"euler_characteristic", f.euler},
          {"genus", f.genus < 0 ? nlohmann::json(nullptr) : nlohmann::json(f.genus)},
          {"closed", f.closed},
          {"extraordinary_vertex_fraction", f.extraordinary_vertex_fraction},
          {"extraordinary_quad_fraction", f.extraordinary_quad_fraction},
          {"creased_edges", f.creased_edges},
          {"corners", f.corners},
          {"holes", f.holes},
          {"boundary_rule", to_string(m.boundary)},
          {"warnings", m.warnings}};
}

std::string histogram_text(const std::map<int, int>& h) {
  std::string s;
  for (auto [k, v] : h) s += (s.empty() ? "" : ", ") + std::to_string(k) + ": " + std::to_string(v);
  return s;
}

int info(const MeshVerbOptions& opts) {
  const ControlMesh mesh = load_mesh(opts.mesh);
  const MeshFacts f = compute_facts(mesh);
  if (opts.json) {
    std::cout << facts_json(mesh, f).dump(2) << "\n";
    return 0;
  }
  std::printf("%s  (%s)\n", printable(mesh.name).c_str(), printable(mesh.source).c_str());
  std::printf("  vertices %d, faces %d, edges %d\n", f.vertices, f.faces, f.edges);
  std::printf("  face sizes   %s\n", histogram_text(f.face_sizes).c_str());
  std::printf("  valences     %s\n", histogram_text(f.valences).c_str());
  std::printf("  boundary edges %d in %d loops, non-manifold edges %d, inconsistently oriented edges %d, degenerate faces %d\n",
              f.boundary_edges, f.boundary_loops, f.non_manifold_edges, f.inconsistent_edges, f.degenerate_faces);
  if (f.non_manifold_vertices) std::printf("  non-manifold vertices %d (pinched: faces meeting at a vertex only)\n", f.non_manifold_vertices);
  std::printf("  components %d, Euler characteristic %d, genus %s, %s\n", f.components, f.euler,
              f.genus < 0 ? "undefined" : std::to_string(f.genus).c_str(), f.closed ? "closed" : "open");
  std::printf("  extraordinary: %.1f%% of vertices, %.1f%% of quads\n", 100 * f.extraordinary_vertex_fraction,
              100 * f.extraordinary_quad_fraction);
  std::printf("  creased edges %d, corners %d, holes %d, boundary rule %s\n", f.creased_edges, f.corners, f.holes,
              to_string(mesh.boundary).c_str());
  if (f.unused_vertices) std::printf("  unused vertices %d\n", f.unused_vertices);
  for (const auto& w : mesh.warnings) std::printf("  warning: %s\n", printable(w).c_str());
  return 0;
}

int list_meshes_cmd() {
  std::printf("%-40s %-8s %8s %8s %8s  %s\n", "name", "kind", "vertices", "faces", "extra%", "description");
  for (const auto& e : list_meshes()) {
    try {
      const ControlMesh m = load_mesh(e.name);
      const MeshFacts f = compute_facts(m);
      const bool quads = f.face_sizes.count(4) && f.face_sizes.at(4) * 2 > f.faces;
      const double extra = quads ? f.extraordinary_quad_fraction : f.extraordinary_vertex_fraction;
      std::printf("%-40s %-8s %8d %8d %7.1f%%  %s%s\n", printable(e.name).c_str(), e.kind.c_str(), f.vertices, f.faces,
                  100 * extra, quads ? "" : "(vertices) ", printable(e.description).c_str());
    } catch (const InputError& err) {
      std::printf("%-40s %-8s %8s %8s %8s  unreadable: %s\n", printable(e.name).c_str(), e.kind.c_str(), "-", "-", "-",
                  printable(err.what()).c_str());
    }
  }
  if (!corpus_dir()) std::printf("(shared corpus not found: set SUBDIVBENCH_DATASETS or place ../shared/datasets beside the checkout)\n");
  return 0;
}

int list_schemes_cmd() {
  if (all_schemes().empty()) {
    std::printf("no schemes built yet\n");
    return 0;
  }
  std::printf("%-24s %-7s %-22s %-7s %-13s %s\n", "scheme", "role", "backends", "levels", "peer", "paper");
  for (const auto& s : all_schemes()) {
    const SchemeInfo& i = s->info();
    std::string backends;
    for (Backend b : i.backends) backends += (backends.empty() ? "" : ",") + std::string(to_string(b));
    std::printf("%-24s %-7s %-22s %-7s %-13s %s\n", i.name.c_str(), std::string(to_string(i.role)).c_str(),
                backends.c_str(), i.level_kind == LevelKind::Depth ? "depth" : "rate N",
                i.peer.empty() ? "-" : i.peer.c_str(), i.paper.c_str());
    for (const ParameterSpec& p : i.parameters)
      std::printf("    %s:%s=V  %s (%s %s..%s%s, default %s)\n", i.name.c_str(), p.name.c_str(), p.description.c_str(),
                  p.integer ? "integer" : "number", format_parameter(p.min, p.integer).c_str(),
                  format_parameter(p.max, p.integer).c_str(),
                  p.step > 0 ? (" in steps of " + format_parameter(p.step, p.integer)).c_str() : "",
                  format_parameter(p.default_value, p.integer).c_str());
  }
  return 0;
}

int list_backends_cmd() {
  std::printf("%-8s %-12s %s\n", "backend", "status", "detail");
  std::printf("%-8s %-12s %s\n", "cpu", "available", "one thread");
  std::printf("%-8s %-12s %u hardware threads (TBB)\n", "cpu-mt", "available", std::thread::hardware_concurrency());
  const gpu::DeviceInfo vk = gpu::probe();
  std::printf("%-8s %-12s %s\n", "vulkan", vk.available ? "available" : "unavailable",
              vk.available ? gpu::summary(vk).c_str() : vk.reason.c_str());
  const gl::DeviceInfo g = gl::probe();
  std::printf("%-8s %-12s %s\n", "opengl", g.available ? "available" : "unavailable", gl::summary(g).c_str());
  return 0;
}

int list(const MeshVerbOptions& opts) {
  if (opts.list_what == "meshes") return list_meshes_cmd();
  if (opts.list_what == "backends") return list_backends_cmd();
  return list_schemes_cmd();
}

}  // namespace

void add_mesh_verbs(CLI::App& app, Verbs& verbs) {
  auto opts = std::make_shared<MeshVerbOptions>();
  auto* list_cmd = app.add_subcommand("list", "List schemes, meshes or backends");
  list_cmd->add_option("what", opts->list_what, "schemes | meshes | backends")
      ->check(CLI::IsMember({"schemes", "meshes", "backends"}));
  verbs["list"] = [opts] { return list(*opts); };

  auto* info_cmd = app.add_subcommand("info", "Facts of a mesh: counts, histograms, genus, extraordinary share");
  info_cmd->add_option("mesh", opts->mesh, "manifest name or path")->required();
  info_cmd->add_flag("--json", opts->json, "print one JSON object");
  verbs["info"] = [opts] { return info(*opts); };
}

Verbs register_commands(CLI::App& app) {
  Verbs verbs;
  add_mesh_verbs(app, verbs);
  add_run_verbs(app, verbs);
  add_gate_verbs(app, verbs);
  add_picture_verbs(app, verbs);
  add_gpu_check_verbs(app, verbs);
  return verbs;
}

int run_selected(const CLI::App& app, const Verbs& verbs) {
  for (const auto* sub : app.get_subcommands()) return verbs.at(sub->get_name())();
  return 2;
}

}  // namespace sdb::app
