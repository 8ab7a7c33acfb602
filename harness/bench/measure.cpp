#include "measure.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <regex>

#include "deviation.h"
#include "errors.h"
#include "facts.h"
#include "manifest.h"
#include "registry.h"
#include "watertight.h"

namespace sdb {
namespace {

// Collects per-repetition times of the benchmarks it sees (and shows nothing).
class CollectingReporter : public benchmark::BenchmarkReporter {
 public:
  bool ReportContext(const Context&) override { return true; }
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs) {
      if (r.run_type != Run::RT_Iteration) continue;
      Samples& s = samples[r.run_name.function_name];  // without the /repeats: suffixes
      if (r.error_occurred) s.error = r.error_message;
      s.time_ms.push_back(r.GetAdjustedRealTime());  // the benchmark's unit is ms
      auto wall = r.counters.find("wall_ms");
      if (wall != r.counters.end()) s.wall_ms.push_back(wall->second.value);
    }
  }
  struct Samples {
    std::vector<double> time_ms, wall_ms;
    std::string error;
  };
  std::map<std::string, Samples> samples;
};

TimeStats stats_of(const std::vector<double>& v) {
  TimeStats t;
  if (v.empty()) return t;
  std::vector<double> s = v;
  std::sort(s.begin(), s.end());
  t.min = s.front(), t.max = s.back();
  t.median = s.size() % 2 ? s[s.size() / 2] : 0.5 * (s[s.size() / 2 - 1] + s[s.size() / 2]);
  t.reps = static_cast<int>(v.size());
  t.samples = v;
  return t;
}

std::string regex_escape(const std::string& s) {
  static const std::regex special(R"([.^$|()\[\]{}*+?\\])");
  return std::regex_replace(s, special, R"(\$&)");
}

bool planted_slowdown(const std::string& scheme) {
  // Test hook for the gate: doubles the work of one scheme (see tests/gate_test.cpp).
  const char* env = std::getenv("SUBDIVBENCH_PLANT_SLOWDOWN");
  return env && scheme == env;
}

}  // namespace

std::string RunSpec::name() const {
  return scheme + "/" + std::string(to_string(backend)) + "/" + mesh + "/" + std::to_string(level);
}

const ControlMesh& MeasureContext::mesh(const std::string& name) {
  auto it = meshes_.find(name);
  if (it == meshes_.end()) it = meshes_.emplace(name, load_mesh(name)).first;
  return it->second;
}

std::shared_ptr<const ControlMesh> MeasureContext::accepted(const std::string& name, const Scheme& scheme) {
  const MeshRequirements& a = scheme.info().accepts;
  // Schemes with the same face requirement get the same accepted mesh (and reference surface).
  const std::string key = name + "|" + std::to_string(int(a.faces)) + std::to_string(a.quadrangulate);
  auto it = accepted_.find(key);
  if (it != accepted_.end()) {
    accept_mesh(*it->second, scheme.info());  // the remaining checks still apply per scheme
    return it->second;
  }
  auto m = std::make_shared<const ControlMesh>(accept_mesh(mesh(name), scheme.info()));
  accepted_[key] = m;
  return m;
}

const LimitEvaluator& MeasureContext::reference(const std::shared_ptr<const ControlMesh>& m, SubdivisionRule rule) {
  auto& slot = references_[m.get()];
  if (!slot) {
    keep_alive_.push_back(m);
    slot = std::make_unique<LimitEvaluator>(*m, rule);
  }
  return *slot;
}

const Tessellation& MeasureContext::dense_reference(const std::shared_ptr<const ControlMesh>& m) {
  auto it = dense_.find(m.get());
  if (it != dense_.end()) return it->second;
  keep_alive_.push_back(m);
  // About two million triangles: dense enough for 1e-4 of the diagonal on the meshes here.
  const int faces = std::max(1, num_faces(*m));
  const int rate = std::clamp(static_cast<int>(std::sqrt(1e6 / faces)) + 1, 3, 33);
  const Scheme* bfr = find_scheme("osd-bfr");
  auto e = bfr->prepare(*m, {Backend::CpuMt, rate, 0});
  e->execute();
  return dense_.emplace(m.get(), e->result()).first->second;
}

void validate_into(RunRow& row, const Tessellation& t, const std::shared_ptr<const ControlMesh>& ref_mesh,
                   SubdivisionRule rule, const MeasureOptions& o, MeasureContext& ctx) {
  const MeshFacts facts = compute_facts(*ref_mesh);
  row.watertight.open_edges = count_open_edges(t);
  row.watertight.seed = o.seed;
  const bool closed = facts.closed && ref_mesh->holes.empty();
  if (closed) {
    const RayCrackReport r = ray_crack_check(t, {o.rays, o.rays, o.seed});
    row.watertight.rays = r.rays;
    row.watertight.ray_cracks = r.cracks;
    if (row.watertight.open_edges > 0 || r.cracks > 0) {
      row.status = "failed";
      row.message = "closed input, but " + std::to_string(row.watertight.open_edges) + " open edges and " +
                    std::to_string(r.cracks) + " ray cracks";
    }
  }
  if (rule == SubdivisionRule::CatmullClark || facts.all_triangles) {
    const DeviationReport d = measure_deviation(t, ctx.reference(ref_mesh, rule));
    row.deviation = {true,  d.pos_max_pct,    d.pos_mean_pct,   d.pos_rms_pct, d.pos_p95_pct, d.pos_max_rel_diag,
                     d.normal_max_deg, d.normal_mean_deg, -1};
    if (o.hausdorff && rule == SubdivisionRule::CatmullClark) row.deviation.hausdorff_rel = hausdorff(t, ctx.dense_reference(ref_mesh)).max();
  }
}

RunRow measure_run(const RunSpec& spec, const MeasureOptions& o, MeasureContext& ctx) {
  const Scheme* scheme = find_scheme(spec.scheme);
  if (!scheme) throw InputError(spec.scheme, "no such scheme (see `subdivbench list schemes`)");
  RunRow row;
  row.scheme = spec.scheme;
  row.backend = std::string(to_string(spec.backend));
  row.mesh = spec.mesh;
  row.level = spec.level;
  row.device = spec.backend == Backend::Vulkan ? ctx.machine().vulkan_device : ctx.machine().cpu_model;
  const SchemeInfo& info = scheme->info();
  row.tessellation = segments_per_edge(info.level_kind, spec.level);
  const RunRequest request{spec.backend, spec.level, o.threads};
  if (auto why = scheme->unsupported(request)) {
    row.status = "unsupported";
    row.message = *why;
    return row;
  }
  const auto accepted = ctx.accepted(spec.mesh, *scheme);
  const MeshFacts facts = compute_facts(ctx.mesh(spec.mesh));
  row.mesh_faces = facts.faces;
  row.mesh_vertices = facts.vertices;
  row.extraordinary_fraction = facts.all_triangles ? facts.extraordinary_vertex_fraction : facts.extraordinary_quad_fraction;
  if (!accepted->warnings.empty() && accepted->warnings.back().rfind("quadrangulated", 0) == 0)
    row.message = "quadrangulated by one Catmull-Clark step";

  std::unique_ptr<Evaluation> eval = scheme->prepare(*accepted, request);
  const auto start = std::chrono::steady_clock::now();
  eval->execute();
  const double once_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const Tessellation& out = eval->result();
  row.triangles = static_cast<long>(out.num_triangles());
  row.vertices = static_cast<long>(out.num_vertices());
  row.bytes_out = static_cast<long>(eval->bytes_out());
  if (o.validate) {
    const auto ref_mesh = out.reference ? out.reference : accepted;
    validate_into(row, out, ref_mesh, info.reference, o, ctx);
  }

  const bool gpu = spec.backend == Backend::Vulkan;
  if (!o.time) {
    row.time_ms = stats_of({once_ms});
    if (auto g = eval->gpu_times(); gpu && g) row.gpu_time_ms = stats_of({g->kernel_ms});
    const double ms = row.gpu_time_ms ? row.gpu_time_ms->median : once_ms;
    row.triangle_rate_mtris = ms > 0 ? row.triangles / (ms * 1e3) : 0;
    return row;
  }
  const bool slow = planted_slowdown(spec.scheme);
  Evaluation* e = eval.get();
  auto* bench = benchmark::RegisterBenchmark(spec.name().c_str(), [e, gpu, slow](benchmark::State& state) {
    double wall = 0;
    for (auto _ : state) {
      const auto t0 = std::chrono::steady_clock::now();
      e->execute();
      if (slow) e->execute();
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      wall += ms;
      if (gpu) {
        const auto g = e->gpu_times();
        state.SetIterationTime((g ? g->kernel_ms * (slow ? 2 : 1) : ms) / 1e3);
      }
    }
    state.counters["wall_ms"] = benchmark::Counter(wall, benchmark::Counter::kAvgIterations);
  });
  bench->Unit(benchmark::kMillisecond)->Repetitions(o.reps)->MinTime(o.min_time_s);
  if (gpu) bench->UseManualTime();
  CollectingReporter collector;
  // Google Benchmark appends /min_time:.../repeats:... to the name it filters on.
  benchmark::RunSpecifiedBenchmarks(&collector, "^" + regex_escape(spec.name()) + "(/|$)");
  benchmark::ClearRegisteredBenchmarks();
  const auto& s = collector.samples[spec.name()];
  if (!s.error.empty()) throw std::runtime_error(spec.name() + ": " + s.error);
  row.time_ms = stats_of(s.wall_ms);
  if (gpu) {
    row.gpu_time_ms = stats_of(s.time_ms);
    if (auto g = e->gpu_times()) {
      row.upload_ms = g->upload_ms;
      row.readback_ms = g->readback_ms;
      for (const auto& p : g->passes) row.gpu_passes.push_back({p.label, p.ms});
    }
  }
  const double ms = gpu ? row.gpu_time_ms->median : row.time_ms.median;
  row.triangle_rate_mtris = ms > 0 ? row.triangles / (ms * 1e3) : 0;
  const double bandwidth = spec.backend == Backend::CpuMt ? ctx.machine().write_bandwidth_mt_gbs
                                                          : ctx.machine().write_bandwidth_gbs;
  if (bandwidth > 0 && row.triangles > 0 && ms > 0)
    row.bandwidth_fraction = (row.bytes_out / (ms * 1e-3)) / (bandwidth * 1e9);
  return row;
}

}  // namespace sdb
