// Developer tool for the geometry-image scheme (not a test, not part of the harness):
//   gim_tool create MESH N...       create images (uses the cache), print creation figures
//   gim_tool export MESH N OUT.obj  write the image's g0 as OBJ (subdivbench takes it as that image)
//   gim_tool time MESH K [REPS]     rough single-thread timing of execute(), beside OpenSubdiv
//                                   uniform refinement with limit projection on the same g0, and
//                                   the vulkan backend's timestamps pass by pass (median of REPS)
//   gim_tool hausdorff MESH N...    fitted surfaces (about 513 samples a side) against MESH's Catmull-Clark
//                                   limit: each vertex's distance to it (max, p95) and the two-sided
//                                   Hausdorff distance, of the diagonal
// For experiments, $GIM_FAIRNESS, $GIM_TOL, $GIM_SWEEPS, $GIM_MINTRI, $GIM_RW and $GIM_INVERSE override
// the creation settings (the cache key follows them).
#include <opensubdiv/far/primvarRefiner.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "datasets/manifest.h"
#include "harness/mesh/mesh_io.h"
#include "harness/mesh/osd_topology.h"
#include "harness/reference/dense_limit.h"
#include "harness/results/statistics.h"
#include "harness/validate/deviation.h"
#include "harness/validate/limit_distance.h"
#include "schemes/geometry-image/closed_mesh.h"
#include "schemes/geometry-image/creation/create.h"
#include "schemes/geometry-image/creation/triangle_mesh.h"
#include "schemes/geometry-image/geometry_image.h"

using namespace sdb;
using namespace sdb::gim;

namespace {

struct Timing {
  double median = 0, min = 0;
};

Timing time_ms(const std::function<void()>& work, int reps) {
  std::vector<double> t;
  work();  // warm up
  for (int r = 0; r < reps; ++r) {
    const auto start = std::chrono::steady_clock::now();
    work();
    t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  return {median(t), *std::min_element(t.begin(), t.end())};
}


// The same work as the harness's osd-uniform peer: PrimvarRefiner::Interpolate per level, Limit
// with tangents, unit normals.
Timing time_osd(const ControlMesh& g0, int level, int reps, long& triangles) {
  namespace Far = OpenSubdiv::Far;
  auto refiner = make_refiner(g0, SubdivisionRule::CatmullClark);
  Far::TopologyRefiner::UniformOptions options(level);
  options.fullTopologyInLastLevel = true;
  refiner->RefineUniform(options);
  std::vector<std::vector<PrimvarPoint>> levels(level + 1);
  for (int l = 0; l <= level; ++l) levels[l].resize(refiner->GetLevel(l).GetNumVertices());
  const int nv = refiner->GetLevel(level).GetNumVertices();
  std::vector<PrimvarPoint> pos(nv), du(nv), dv(nv);
  std::vector<Point3> normals(nv);
  triangles = 2L * refiner->GetLevel(level).GetNumFaces();
  return time_ms(
      [&] {
        for (size_t v = 0; v < g0.positions.size(); ++v)
          for (int k = 0; k < 3; ++k) levels[0][v].p[k] = g0.positions[v][k];
        Far::PrimvarRefiner primvar(*refiner);
        for (int l = 1; l <= level; ++l) {
          PrimvarPoint* dst = levels[l].data();
          primvar.Interpolate(l, levels[l - 1].data(), dst);
        }
        PrimvarPoint *p = pos.data(), *a = du.data(), *b = dv.data();
        primvar.Limit(levels[level].data(), p, a, b);
        for (int v = 0; v < nv; ++v) {
          const float* s = du[v].p;
          const float* t = dv[v].p;
          const float n[3] = {s[1] * t[2] - s[2] * t[1], s[2] * t[0] - s[0] * t[2], s[0] * t[1] - s[1] * t[0]};
          const float inv = 1.0f / std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
          normals[v] = {n[0] * inv, n[1] * inv, n[2] * inv};
        }
      },
      reps);
}

CreationOptions options_from_environment() {
  CreationOptions o;
  if (const char* f = std::getenv("GIM_FAIRNESS")) o.fit.fairness = std::atof(f);
  if (const char* f = std::getenv("GIM_REPROJECT")) o.fit.reprojections = std::atoi(f);
  if (const char* f = std::getenv("GIM_TOL")) o.parametrization.tolerance = std::atof(f);
  if (const char* f = std::getenv("GIM_SWEEPS")) o.parametrization.max_sweeps = std::atoi(f);
  if (const char* f = std::getenv("GIM_MINTRI")) o.parametrization.min_triangles = std::atoi(f);
  if (const char* f = std::getenv("GIM_RW")) o.parametrization.reweighting_rounds = std::atoi(f);
  if (const char* f = std::getenv("GIM_INVERSE")) o.parametrization.inverse_weight = std::atof(f);
  return o;
}

int hausdorff_table(const std::string& name, const std::vector<int>& sizes) {
  const ControlMesh mesh = load_mesh(name);
  GeometryImageCreator creator(mesh, options_from_environment());
  const LimitEvaluator& limit = creator.limit();
  const LimitProjector projector(limit);
  const DenseLimit dense = dense_limit(limit);
  const auto scheme = make_geometry_image_scheme();
  for (int n : sizes) {
    const CreatedImage made = creator.create(n);
    int level = 0;
    while (level_size(n, level) < 500) ++level;
    auto eval = scheme->prepare(closed_mesh(made.image, "g0", ""), default_request(scheme->info(), Backend::Cpu, level));
    eval->execute();
    const LimitDistance d = distance_by_nearest_point(eval->result(), projector);
    const HausdorffReport h = hausdorff(eval->result(), dense.surface, *dense.scene);
    const long turned = std::count_if(d.report.vertex_deg.begin(), d.report.vertex_deg.end(), [](float a) { return a > 10; });
    // Where the largest distance and the largest normal angle are, in image coordinates.
    const long side = level_size(n, level);
    const auto far = std::max_element(d.vertex_rel_diag.begin(), d.vertex_rel_diag.end()) - d.vertex_rel_diag.begin();
    const auto bent = std::max_element(d.report.vertex_deg.begin(), d.report.vertex_deg.end(),
                                       [](float a, float b) { return std::isnan(b) ? false : std::isnan(a) || a < b; }) -
                      d.report.vertex_deg.begin();
    const double scale = double(n - 1) / double(side - 1);
    std::printf("%s m=%d k=%d: vertices max %.5f p95 %.5f; Hausdorff %.5f (forward %.5f, backward %.5f) of the "
                "diagonal from the limit; normals max %.1f deg, %ld past 10 deg; fit %.0f ms; farthest at image "
                "(%.2f, %.2f), most turned at (%.2f, %.2f)\n",
                name.c_str(), n, level, d.report.pos_max_rel_diag, d.pos_p95_rel_diag, h.max(), h.forward_max,
                h.backward_max, d.report.normal_max_deg, turned, made.report.fit_ms, (far % side) * scale,
                (far / side) * scale, (bent % side) * scale, (bent / side) * scale);
  }
  return 0;
}

int create(const std::string& name, const std::vector<int>& sizes) {
  GeometryImageCreator creator(load_mesh(name), options_from_environment());
  if (std::getenv("GIM_TOOL_PARAM")) {
    const SphericalParametrization& p = creator.parametrization();
    std::printf("%s: %zu vertices, centred stretch %.3f, relaxed %.3f after %d sweeps, %d folded\n", name.c_str(),
                p.sphere.size(), p.centred_stretch, p.stretch, p.sweeps, p.folded_triangles);
  }
  for (int n : sizes) {
    const CreatedImage made = creator.create(n);
    const CreationReport& r = made.report;
    std::printf("%s n=%d %s parametrize %.0f ms (L2 stretch %.3f), sample %.0f ms, fit %.0f ms (%d unknowns, %ld samples, "
                "CG %d iterations), rms residual %.3g  %s\n",
                name.c_str(), n, r.from_cache ? "[cached]" : "", r.parametrize_ms, r.stretch, r.sample_ms, r.fit_ms,
                r.unknowns, r.samples, r.cg_iterations, r.rms_residual, r.cache_path.c_str());
  }
  return 0;
}

// Median GPU time of every pass over `reps` frames (the vulkan evaluation's timestamps).
void time_vulkan(const Scheme& scheme, const ControlMesh& mesh, int level, int reps, const char* plan) {
  if (auto why = scheme.unsupported(default_request(scheme.info(), Backend::Vulkan, level))) {
    std::printf("geometry-image %-8s vulkan: %s\n", plan, why->c_str());
    return;
  }
  auto eval = scheme.prepare(mesh, default_request(scheme.info(), Backend::Vulkan, level));
  std::vector<std::vector<double>> per_pass;
  std::vector<std::string> labels;
  std::vector<double> kernel;
  for (int r = 0; r <= reps; ++r) {
    eval->execute();
    eval->result();  // the readback, timed separately
    const auto t = eval->gpu_times();
    if (!t) {
      std::printf("geometry-image %-8s vulkan: no timestamps\n", plan);
      return;
    }
    if (r == 0) {  // warm-up
      for (const auto& p : t->passes) labels.push_back(p.label);
      per_pass.resize(labels.size());
      continue;
    }
    kernel.push_back(t->kernel_ms);
    for (size_t i = 0; i < t->passes.size(); ++i) per_pass[i].push_back(t->passes[i].ms);
  }
  const double tris = static_cast<double>(eval->result().num_triangles());
  std::printf("geometry-image %-8s vulkan k=%d: kernel median %.3f ms, %.1f M tri/s; passes:", plan, level,
              median(kernel), tris / median(kernel) / 1e3);
  for (size_t i = 0; i < labels.size(); ++i) std::printf(" %s %.3f", labels[i].c_str(), median(per_pass[i]));
  std::printf("\n");
}

int time(const std::string& name, int level, int reps) {
  const ControlMesh mesh = load_mesh(name);
  for (PassPlan plan : {PassPlan::Fused, PassPlan::PerMask}) {
    const auto scheme = make_geometry_image_scheme(plan);
    for (Backend b : {Backend::Cpu, Backend::CpuMt}) {
      auto eval = scheme->prepare(mesh, default_request(scheme->info(), b, level));
      const Timing t = time_ms([&] { eval->execute(); }, reps);
      const double tris = static_cast<double>(eval->result().num_triangles());
      std::printf("geometry-image %-8s %-6s k=%d: median %.3f ms (min %.3f), %.0f triangles, %.1f M tri/s\n",
                  plan == PassPlan::Fused ? "fused" : "per-mask", std::string(to_string(b)).c_str(), level, t.median,
                  t.min, tris, tris / t.median / 1e3);
    }
    time_vulkan(*scheme, mesh, level, reps, plan == PassPlan::Fused ? "fused" : "per-mask");
  }
  const auto image = image_from_closed_mesh(mesh);
  if (image) {
    long tris = 0;
    const Timing t = time_osd(closed_mesh(*image, "g0", ""), level, reps, tris);
    std::printf("osd-uniform             cpu    k=%d: median %.3f ms (min %.3f), %ld triangles, %.1f M tri/s\n", level,
                t.median, t.min, tris, static_cast<double>(tris) / t.median / 1e3);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::vector<std::string> args(argv + 1, argv + argc);
    if (args.size() >= 3 && args[0] == "create") {
      std::vector<int> sizes;
      for (size_t i = 2; i < args.size(); ++i) sizes.push_back(std::stoi(args[i]));
      return create(args[1], sizes);
    }
    if (args.size() >= 3 && args[0] == "hausdorff") {
      std::vector<int> sizes;
      for (size_t i = 2; i < args.size(); ++i) sizes.push_back(std::stoi(args[i]));
      return hausdorff_table(args[1], sizes);
    }
    if (args.size() == 4 && args[0] == "export") {
      const CreatedImage made = create_geometry_image(load_mesh(args[1]), {.size = std::stoi(args[2])});
      write_obj(closed_mesh(made.image, args[1] + "-gim", args[3]), args[3]);
      return 0;
    }
    if (args.size() >= 3 && args[0] == "time") return time(args[1], std::stoi(args[2]), args.size() > 3 ? std::stoi(args[3]) : 21);
    std::fprintf(stderr, "usage: gim_tool create MESH N... | hausdorff MESH N... | export MESH N OUT.obj | time MESH K [REPS]\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}
