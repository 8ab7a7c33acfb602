#include "harness/bench/measure.h"

#include <sys/resource.h>
#include <unistd.h>

#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <numeric>
#include <random>
#include <regex>

#include "datasets/manifest.h"
#include "harness/bench/progress.h"
#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/mesh/acceptance.h"
#include "harness/mesh/facts.h"
#include "harness/results/bound_judgement.h"
#include "harness/results/statistics.h"
#include "harness/validate/deviation.h"
#include "harness/validate/deviation_ply.h"
#include "harness/validate/watertight.h"

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

// Shows runs on a display reporter (the console) while collecting them.
class TeeReporter : public CollectingReporter {
 public:
  explicit TeeReporter(benchmark::BenchmarkReporter* display) : display_(display) {}
  bool ReportContext(const Context& c) override { return display_ ? display_->ReportContext(c) : true; }
  void ReportRuns(const std::vector<Run>& runs) override {
    CollectingReporter::ReportRuns(runs);
    if (display_) display_->ReportRuns(runs);
  }
  void Finalize() override {
    if (display_) display_->Finalize();
  }

 private:
  benchmark::BenchmarkReporter* display_;
};

TimeStats stats_of(const std::vector<double>& v) {
  TimeStats t;
  if (v.empty()) return t;
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  t.min = *lo, t.max = *hi;
  t.median = median(v);
  t.reps = static_cast<int>(v.size());
  t.samples = v;
  return t;
}

std::string regex_escape(const std::string& s) {
  static const std::regex special(R"([.^$|()\[\]{}*+?\\])");
  return std::regex_replace(s, special, R"(\$&)");
}

}  // namespace

// The `cpu` backend means one thread for every scheme: work that libraries fan out through TBB
// (Embree's geometry commit, say) stays in a one-thread arena.
void execute_on(Evaluation& e, Backend backend) {
  if (backend != Backend::Cpu) {
    e.execute();
    return;
  }
  static thread_local tbb::task_arena one_thread(1);
  one_thread.execute([&] { e.execute(); });
}

std::optional<std::string> declined(const Scheme& scheme, const RunRequest& request) {
  if (auto why = scheme.unsupported(request)) return why;
  const auto& declared = scheme.info().backends;
  if (std::find(declared.begin(), declared.end(), request.backend) != declared.end()) return std::nullopt;
  std::string names;
  for (Backend b : declared) names += (names.empty() ? "" : ", ") + std::string(to_string(b));
  return scheme.info().name + " runs on " + names + " only";
}

std::optional<Backend> peer_backend_for(const SchemeInfo& info, Backend backend) {
  const Scheme* peer = info.peer.empty() ? nullptr : find_scheme(info.peer);
  if (!peer || peer->info().backends.empty()) return std::nullopt;
  const auto& b = peer->info().backends;
  if (std::find(b.begin(), b.end(), backend) != b.end()) return backend;
  for (auto it = b.rbegin(); it != b.rend(); ++it)
    if (!is_gpu(*it)) return *it;
  return std::nullopt;
}

const ControlMesh& MeasureContext::mesh(const std::string& name) {
  auto it = meshes_.find(name);
  if (it == meshes_.end()) {
    const ControlMesh loaded = load_mesh(name);
    it = meshes_.emplace(name, placed_mesh(loaded)).first;
    placements_[name] = placement_of(loaded);
  }
  return it->second;
}

std::shared_ptr<const ControlMesh> MeasureContext::input(const std::string& name) {
  auto& slot = inputs_[name];
  if (!slot) slot = std::make_shared<const ControlMesh>(mesh(name));
  return slot;
}

Placement MeasureContext::placement(const std::string& name) {
  mesh(name);
  return placements_.at(name);
}

std::shared_ptr<const ControlMesh> MeasureContext::accepted(const std::string& name, const Scheme& scheme) {
  const MeshRequirements& a = scheme.info().accepts;
  // Schemes with the same face requirement get the same accepted mesh (and reference surface).
  const std::string key =
      name + "|" + std::to_string(int(a.faces)) + std::to_string(a.quadrangulate) + std::to_string(a.split_polygons);
  auto it = accepted_.find(key);
  if (it != accepted_.end()) {
    accept_mesh(*it->second, scheme.info(), facts(*it->second));  // the remaining checks still apply per scheme
    return it->second;
  }
  const ControlMesh& given = mesh(name);
  auto m = std::make_shared<const ControlMesh>(accept_mesh(given, scheme.info(), facts(given)));
  accepted_[key] = m;
  return m;
}

namespace {

// Plain structs without padding: their bytes are their values.
static_assert(sizeof(EdgeCrease) == 2 * sizeof(int) + sizeof(float) && sizeof(VertexCorner) == sizeof(int) + sizeof(float));

template <typename T>
void hash_bytes(size_t& h, const std::vector<T>& v) {
  const std::string_view bytes(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  h = h * 1099511628211ull ^ std::hash<std::string_view>{}(bytes);
}

// Identifies a surface: positions, faces and tags (two meshes with equal keys have the same limit).
size_t content_key(const ControlMesh& m) {
  size_t h = 14695981039346656037ull;
  hash_bytes(h, m.positions);
  hash_bytes(h, m.face_sizes);
  hash_bytes(h, m.face_vertices);
  hash_bytes(h, m.holes);
  hash_bytes(h, m.creases);
  hash_bytes(h, m.corners);
  return h * 31 + static_cast<size_t>(m.boundary);
}

}  // namespace

const MeshFacts& MeasureContext::facts(const ControlMesh& m) {
  const size_t key = content_key(m);
  auto it = facts_.find(key);
  if (it == facts_.end()) it = facts_.emplace(key, compute_facts(m)).first;
  return it->second;
}

const LimitEvaluator& MeasureContext::reference(const std::shared_ptr<const ControlMesh>& m, SubdivisionRule rule) {
  auto& slot = references_[{content_key(*m), int(rule)}];
  if (!slot) {
    keep_alive_.push_back(m);
    slot = std::make_unique<LimitEvaluator>(*m, rule);
  }
  return *slot;
}

const DenseLimit& MeasureContext::dense_reference(const std::shared_ptr<const ControlMesh>& m, SubdivisionRule rule) {
  const std::pair<size_t, int> key{content_key(*m), int(rule)};
  auto it = dense_.find(key);
  if (it == dense_.end()) it = dense_.emplace(key, dense_limit(reference(m, rule))).first;
  return it->second;
}

const LimitProjector& MeasureContext::projector(const std::shared_ptr<const ControlMesh>& m, SubdivisionRule rule) {
  auto& slot = projectors_[{content_key(*m), int(rule)}];
  if (!slot) slot = std::make_unique<LimitProjector>(reference(m, rule));
  return *slot;
}

namespace {

// What is past `bound` of a position (fraction of the diagonal) and a normal figure, in words.
// A row past its scheme's declared bound fails, like a crack: the scheme promised the bound.
void judge_deviation(RunRow& row) {
  const BoundJudgement j = judge_bounds(row);
  if (j.state != BoundState::Past) return;
  row.status = RunStatus::Failed;
  row.message += (row.message.empty() ? "" : "; ") + j.words;
}

// The scheme's coords are on a mesh of its own (a fitted image's g0), not on the accepted mesh.
bool coords_on_own_mesh(const Tessellation& t, const ControlMesh& accepted) {
  return t.reference && content_key(*t.reference) != content_key(accepted);
}

// The output's coords are on a mesh whose limit is the input's: the accepted mesh, unless its
// polygons were split or the scheme's coords are on a mesh of its own.
bool coords_on_input(const Tessellation& t, const JudgedSurfaces& s) {
  return !t.coords.empty() && s.accepted_keeps_limit && !coords_on_own_mesh(t, *s.accepted);
}

// NaN where no normal was compared (the output or the reference has none anywhere).
double normal_figure(const DeviationReport& d, double figure) {
  return d.vertices > d.normal_undefined ? figure : std::numeric_limits<double>::quiet_NaN();
}

// The vertices the deviation left out, said in the row: an exclusion is the input's claim, counted.
void note_left_out(RunRow& row, const DeviationReport& d) {
  auto note = [&](long n, const char* where) {
    if (n > 0) row.message += (row.message.empty() ? "" : "; ") + std::to_string(n) + " output vertices " + where;
  };
  note(d.no_limit, "on faces with no limit surface (holes, or boundary faces under interpolateboundary 0): not in the deviation");
  note(d.no_size, "on faces of no size (one vertex repeated): not in the deviation");
  if (d.vertices == 0) row.message += (row.message.empty() ? "" : "; ") + std::string("no vertex to measure the deviation at");
}

}  // namespace

bool accepted_keeps_limit(const ControlMesh& accepted) {
  const auto& w = accepted.warnings;
  return w.empty() || w.back().rfind("faces of more than four sides split", 0) != 0;
}

JudgedSurfaces judged_surfaces(const std::string& mesh, const Scheme& scheme, MeasureContext& ctx) {
  JudgedSurfaces s;
  s.accepted = ctx.accepted(mesh, scheme);
  s.input = ctx.input(mesh);
  s.accepted_keeps_limit = accepted_keeps_limit(*s.accepted);
  s.rule = scheme.info().reference;
  return s;
}

LimitDistance input_limit_distance(const Tessellation& t, const JudgedSurfaces& s, MeasureContext& ctx) {
  if (coords_on_input(t, s)) return distance_at_coords(t, ctx.reference(s.accepted, s.rule));
  return distance_by_nearest_point(t, ctx.projector(s.input, s.rule));
}

void validate_into(RunRow& row, const Tessellation& t, const JudgedSurfaces& s, const MeasureOptions& o,
                   MeasureContext& ctx) {
  if (const long bad = positions_out_of_range(t.positions)) {
    // Embree aborts the process on coordinates past its range, and a NaN has no deviation.
    row.status = RunStatus::Failed;
    char range[32];
    std::snprintf(range, sizeof range, "%g", kEmbreeRange);
    row.message = std::to_string(bad) + " output positions are NaN, infinite or beyond " + range +
                  " (the input is placed at unit size): nothing validated";
    return;
  }
  const SubdivisionRule rule = s.rule;
  const MeshFacts& facts = ctx.facts(*s.accepted);
  row.watertight.open_edges = count_open_edges(t);
  row.watertight.seed = o.seed;
  const bool closed = facts.closed && s.accepted->holes.empty();
  if (closed) {
    const RayCrackReport r = ray_crack_check(t, {o.rays, o.rays, o.seed});
    row.watertight.rays = r.rays;
    row.watertight.ray_cracks = r.cracks;
    if (row.watertight.open_edges > 0 || r.cracks > 0) {
      row.status = RunStatus::Failed;
      row.message = "closed input, but " + std::to_string(row.watertight.open_edges) + " open edges and " +
                    std::to_string(r.cracks) + " ray cracks";
    }
  }
  // The yardstick's mesh: the input's limit, reached through the accepted mesh where the coords are on it.
  const bool own_coords = coords_on_own_mesh(t, *s.accepted);
  const bool at_coords = coords_on_input(t, s);
  const std::shared_ptr<const ControlMesh>& limit_mesh = at_coords ? s.accepted : s.input;
  if (rule == SubdivisionRule::Loop && !ctx.facts(*limit_mesh).all_triangles) return;  // no Loop limit to compare with
  try {
    if (t.triangles.empty()) return;
    // By nearest points (no coords on the input) the yardstick is a LimitProjector, the costliest.
    const bool input_figure = o.unjudged_deviation || at_coords || bound_declared(row.bound);
    const LimitDistance d = input_figure ? input_limit_distance(t, s, ctx) : LimitDistance{};
    const DeviationReport& r = d.report;
    if (input_figure) {
      if (!o.deviation_ply.empty()) write_deviation_ply(t, r, o.deviation_ply, ctx.placement(row.mesh));
      row.deviation = {true, r.pos_max_pct, r.pos_mean_pct, r.pos_rms_pct, r.pos_p95_pct, r.pos_max_rel_diag,
                       normal_figure(r, r.normal_max_deg), normal_figure(r, r.normal_mean_deg), -1, r.normal_undefined,
                       d.pos_p95_rel_diag, d.nearest_point ? "nearest-point" : "surface-coords", std::nullopt};
      if (r.normal_undefined > 0)
        row.message += std::string(row.message.empty() ? "" : "; ") + std::to_string(r.normal_undefined) + " of " +
                       std::to_string(r.vertices) + " vertices without a normal to compare (" +
                       std::to_string(r.normal_undefined - r.normal_declared) + " where the limit has none, " +
                       std::to_string(r.normal_declared) + " where the scheme gives none)";
      note_left_out(row, r);
    }
    // The scheme's exactness on its own control mesh, the second figure (the first one where that
    // mesh is the input: an image's own g0 given as the mesh).
    if (t.reference && !t.coords.empty()) {
      const LimitDistance own = own_coords   ? distance_at_coords(t, ctx.reference(t.reference, rule))
                                : at_coords ? d
                                             : distance_at_coords(t, ctx.reference(s.accepted, rule));
      const DeviationReport& o_r = own.report;
      row.deviation.own = DeviationFigures::Own{o_r.pos_max_rel_diag, own.pos_p95_rel_diag, o_r.pos_max_pct,
                                                o_r.pos_p95_pct, normal_figure(o_r, o_r.normal_max_deg)};
    }
  } catch (const Unsupported& e) {
    // The yardstick cannot be built (OpenSubdiv's own limits): the row keeps its watertightness.
    row.message += std::string(row.message.empty() ? "" : "; ") + "no deviation measured: " + e.what();
    return;
  }
  judge_deviation(row);
  if (o.hausdorff && !(o.hausdorff_only_without_coords && at_coords)) {
    const DenseLimit& dense = ctx.dense_reference(limit_mesh, rule);
    row.deviation.hausdorff_rel = hausdorff(t, dense.surface, *dense.scene).max();
  }
}

// The options that decide what a validation computes (VerdictSubject::checks).
std::string validation_checks(const MeasureOptions& o) {
  return "rays " + std::to_string(o.rays) + " seed " + std::to_string(o.seed) + (o.hausdorff ? " hausdorff" : "") +
         (o.hausdorff_only_without_coords ? " without-coords" : "") + (o.unjudged_deviation ? " unjudged" : "");
}

void validate_once(RunRow& row, const Tessellation& t, const JudgedSurfaces& s, const MeasureOptions& o,
                   MeasureContext& ctx) {
  const VerdictSubject subject{row.spec,          row.mesh,  row.level,     s.input.get(),
                               s.accepted.get(),  row.bound, row.own_bound, validation_checks(o)};
  const bool shared = o.deviation_ply.empty();
  if (shared) {
    if (const ValidatedOutputs::Earlier* earlier = ctx.validated_outputs().find(subject, t)) {
      apply_verdict(row, earlier->verdict);
      row.validation_of = earlier->run;
      return;
    }
  }
  // Validated on a blank row carrying what validation reads (its mesh and bounds): the verdict
  // alone, which this row and any row with the same bytes take.
  RunRow blank;
  blank.mesh = row.mesh, blank.bound = row.bound, blank.own_bound = row.own_bound;
  validate_into(blank, t, s, o, ctx);
  Verdict verdict{blank.watertight, blank.deviation, blank.status == RunStatus::Failed, blank.message};
  apply_verdict(row, verdict);
  if (shared) ctx.validated_outputs().remember(subject, t, row.name(), std::move(verdict));
}

namespace {

benchmark::internal::Benchmark* register_timing(const std::string& name, std::function<Evaluation*()> eval,
                                                Backend backend) {
  const bool gpu = is_gpu(backend);
  auto* bench = benchmark::RegisterBenchmark(name.c_str(), [eval, gpu, backend](benchmark::State& state) {
    Evaluation* e = eval();
    double wall = 0;
    for (auto _ : state) {
      const auto t0 = std::chrono::steady_clock::now();
      execute_on(*e, backend);
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      wall += ms;
      if (gpu) {
        const auto g = e->gpu_times();
        state.SetIterationTime((g ? g->kernel_ms : ms) / 1e3);
      }
    }
    state.counters["wall_ms"] = benchmark::Counter(wall, benchmark::Counter::kAvgIterations);
    state.counters["triangles"] = static_cast<double>(e->result().num_triangles());
    state.counters["vertices"] = static_cast<double>(e->result().num_vertices());
    state.counters["rate"] = benchmark::Counter(static_cast<double>(e->result().num_triangles()),
                                                benchmark::Counter::kIsIterationInvariantRate);
    state.counters["bytes"] = benchmark::Counter(static_cast<double>(e->bytes_out()),
                                                 benchmark::Counter::kIsIterationInvariantRate, benchmark::Counter::kIs1024);
  });
  bench->Unit(benchmark::kMillisecond);
  if (gpu) bench->UseManualTime();
  return bench;
}

double bandwidth_of(const MachineInfo& machine, Backend backend) {
  switch (backend) {
    case Backend::CpuMt: return machine.write_bandwidth_mt_gbs;
    case Backend::Vulkan:
    case Backend::OpenGl: return machine.gpu_write_bandwidth_gbs;
    case Backend::Cpu: break;
  }
  return machine.write_bandwidth_gbs;
}

void fill_timing(RunRow& row, const CollectingReporter::Samples& s, Evaluation* e, bool gpu, const MachineInfo& machine) {
  if (!s.error.empty()) throw std::runtime_error(row.name() + ": " + s.error);
  row.time_ms = stats_of(s.wall_ms);
  if (gpu) {
    row.gpu_time_ms = stats_of(s.time_ms);
    if (auto g = e->gpu_times()) {
      row.upload_ms = g->upload_ms;
      row.readback_ms = g->readback_ms;
      row.gpu_passes = g->passes;
    }
  }
  const double ms = gpu ? row.gpu_time_ms->median : row.time_ms.median;
  row.triangle_rate_mtris = ms > 0 ? row.triangles / (ms * 1e3) : 0;
  const double bandwidth = bandwidth_of(machine, row.backend);
  if (bandwidth > 0 && row.triangles > 0 && ms > 0) row.bandwidth_fraction = (row.bytes_out / (ms * 1e-3)) / (bandwidth * 1e9);
}

// A run as the rows record it before anything is measured: what it is, its policy (peer, bound,
// parameters), and "unsupported" when the scheme declines the request. Throws InputError when
// the scheme refuses the mesh.
struct DescribedRun {
  RunRow row;
  const Scheme* scheme = nullptr;
  RunRequest request;
  std::shared_ptr<const ControlMesh> accepted;
  JudgedSurfaces surfaces;
};

// The process's mapped address space now (/proc/self/statm's first field), 0 where unknown.
double address_space_in_use() {
  long pages = 0;
  if (FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%ld", &pages) != 1) pages = 0;
    std::fclose(f);
  }
  return double(pages) * double(sysconf(_SC_PAGE_SIZE));
}

// Memory a run may use: the machine's, or less where the process's address space is limited.
double memory_for_runs() {
  double bytes = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  rlimit as{};
  if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY)
    bytes = std::min(bytes, double(as.rlim_cur) - address_space_in_use());  // the libraries' mappings are in it
  return bytes;
}

// Refused before anything is allocated: a run that cannot fit would end in bad_alloc, or on an
// overcommitting kernel in the OOM killer. The scheme's estimate of its peak (Scheme::estimated_peak_bytes),
// not the output alone: osd-uniform on the frog stand-in at depth 7 passed an output estimate of
// 2.5 GiB and died of bad_alloc under 6 GiB.
std::optional<std::string> too_large(const Scheme& scheme, const ControlMesh& accepted, const RunRequest& request) {
  const double triangles = double(scheme.estimated_triangles(accepted, request));
  const double need = scheme.estimated_peak_bytes(accepted, request), have = 0.75 * memory_for_runs();
  // Past 2^31 triangles the outputs' 32-bit indices cannot name the vertices, whatever the memory.
  if (triangles >= 0 && need <= have && triangles < 2e9) return std::nullopt;
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "a run of about %.3g output triangles needs about %.3g GiB at its peak, more than the %.3g GiB this process may use",
                triangles, need / (1 << 30), std::max(have, 0.0) / (1 << 30));
  return std::string(buf);
}

RunRow policy_row(const RunSpec& spec, const ResolvedScheme& resolved, const MachineInfo& m) {
  const SchemeInfo& info = resolved.scheme->info();
  RunRow row;
  row.scheme = info.name;
  row.spec = resolved.spec;
  row.role = std::string(to_string(info.role));
  row.params.insert(resolved.parameters.values().begin(), resolved.parameters.values().end());
  row.backend = spec.backend;
  row.mesh = spec.mesh;
  row.level = spec.level;
  row.peer = info.peer;
  row.peer_backend = peer_backend_for(info, spec.backend);
  row.bound = info.bound;
  row.own_bound = info.own_bound;
  row.device = spec.backend == Backend::Vulkan ? m.vulkan_device : spec.backend == Backend::OpenGl ? m.opengl_renderer : m.cpu_model;
  row.tessellation = segments_per_edge(info.level_kind, spec.level);
  return row;
}

DescribedRun describe_run(const RunSpec& spec, const MeasureOptions& o, MeasureContext& ctx) {
  const ResolvedScheme resolved = resolve_scheme(spec.scheme);
  DescribedRun d;
  d.scheme = resolved.scheme;
  d.request = {spec.backend, spec.level, o.threads, resolved.parameters};
  d.row = policy_row(spec, resolved, ctx.machine());
  RunRow& row = d.row;
  if (auto why = declined(*d.scheme, d.request)) {
    row.status = RunStatus::Unsupported;
    row.message = *why;
    return d;
  }
  d.surfaces = judged_surfaces(spec.mesh, *d.scheme, ctx);
  d.accepted = d.surfaces.accepted;
  if (auto why = too_large(*d.scheme, *d.accepted, d.request)) {
    row.status = RunStatus::Unsupported;
    row.message = *why;
    return d;
  }
  const MeshFacts& facts = ctx.facts(ctx.mesh(spec.mesh));
  row.mesh_faces = facts.faces;
  row.mesh_vertices = facts.vertices;
  row.extraordinary_fraction = facts.all_triangles ? facts.extraordinary_vertex_fraction : facts.extraordinary_quad_fraction;
  const auto& w = d.accepted->warnings;
  if (!w.empty() && w.back().rfind("quadrangulated", 0) == 0) row.message = "quadrangulated by one Catmull-Clark step";
  if (!d.surfaces.accepted_keeps_limit) row.message = "faces of more than four sides split into quads and a triangle";
  // Where the row approximates a limit its scheme reproduces in other runs (a semi-sharp crease
  // still active at this depth, limit projection off), the bound, that promise, does not apply.
  const SchemeInfo& info = d.scheme->info();
  const bool reproduces = reproduces_limit(info, d.request, *d.accepted);
  row.limit = std::string(to_string(reproduces ? LimitClaim::Reproduces : LimitClaim::Approximates));
  if (!reproduces && info.limit != LimitClaim::Approximates) row.bound = {};
  return d;
}

void record_output(RunRow& row, Evaluation& e) {
  const Tessellation& out = e.result();
  row.triangles = static_cast<long>(out.num_triangles());
  row.vertices = static_cast<long>(out.num_vertices());
  row.bytes_out = static_cast<long>(e.bytes_out());
}

void enter_stage(const MeasureOptions& o, const char* stage, const RunRow& row) {
  if (o.on_stage) o.on_stage(stage, row);
}

}  // namespace

RunRow describe_spec(const RunSpec& spec, const MachineInfo& machine) {
  return policy_row(spec, resolve_scheme(spec.scheme), machine);
}

namespace {
thread_local MeasureObserver* observer = nullptr;
}  // namespace

MeasureObserver::MeasureObserver(std::function<void(const RunSpec&)> b, std::function<void(const RunRow&)> e)
    : began(std::move(b)), ended(std::move(e)), outer_(observer) {
  observer = this;
}
MeasureObserver::~MeasureObserver() { observer = outer_; }

namespace {

RunRow measure_one(const RunSpec& spec, const MeasureOptions& o, MeasureContext& ctx);

}  // namespace

RunRow measure_run(const RunSpec& spec, const MeasureOptions& o, MeasureContext& ctx) {
  MeasureObserver* const seen_by = observer;
  if (seen_by && seen_by->began) seen_by->began(spec);
  RunRow row = measure_one(spec, o, ctx);
  if (seen_by && seen_by->ended) seen_by->ended(row);
  return row;
}

namespace {

RunRow measure_one(const RunSpec& spec, const MeasureOptions& o, MeasureContext& ctx) {
  DescribedRun d = describe_run(spec, o, ctx);
  RunRow& row = d.row;
  if (row.status == RunStatus::Unsupported) return row;
  enter_stage(o, "prepare", row);
  std::unique_ptr<Evaluation> eval;
  try {
    eval = d.scheme->prepare(*d.accepted, d.request);
  } catch (const Unsupported& e) {
    // A device or size limit that depends on the mesh (its output past the device's memory, say).
    row.status = RunStatus::Unsupported;
    row.message = e.what();
    return row;
  } catch (const InputError& e) {
    if (!o.refusals_as_rows) throw;
    row.status = RunStatus::Unsupported;
    row.message = e.what();
    return row;
  }
  for (const std::string& note : eval->notes()) row.message += (row.message.empty() ? "" : "; ") + note;
  enter_stage(o, "execute", row);
  const auto start = std::chrono::steady_clock::now();
  execute_on(*eval, spec.backend);
  const double once_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  record_output(row, *eval);
  if (o.validate) {
    enter_stage(o, "validate", row);
    validate_once(row, eval->result(), d.surfaces, o, ctx);
  }
  const bool gpu = is_gpu(spec.backend);
  if (!o.time) {
    CollectingReporter::Samples once;
    once.wall_ms = {once_ms};
    if (auto g = eval->gpu_times()) once.time_ms = {g->kernel_ms};
    fill_timing(row, once, eval.get(), gpu && !once.time_ms.empty(), ctx.machine());
    return row;
  }
  enter_stage(o, "time", row);
  Evaluation* e = eval.get();
  register_timing(spec.name(), [e] { return e; }, spec.backend)->Repetitions(o.reps)->MinTime(o.min_time_s);
  CollectingReporter collector;
  // Google Benchmark appends /min_time:.../repeats:... to the name it filters on.
  benchmark::RunSpecifiedBenchmarks(&collector, "^" + regex_escape(spec.name()) + "(/|$)");
  benchmark::ClearRegisteredBenchmarks();
  fill_timing(row, collector.samples[spec.name()], e, gpu, ctx.machine());
  return row;
}

// The calibration probe as a benchmark: a streaming store over 64 MiB, one thread on `cpu`, TBB's
// threads on `cpu-mt`. Run once per round beside the schemes, it gives the gate a paired unit
// for rows that have no peer (the peers at the root, osd-bfr).
class WriteProbe final : public Evaluation {
 public:
  explicit WriteProbe(Backend backend) : backend_(backend), buffer_((size_t(64) << 20) / sizeof(float)) {}
  void execute() override {
    value_ += 1.0f;
    if (backend_ == Backend::CpuMt) {
      tbb::parallel_for(tbb::blocked_range<size_t>(0, buffer_.size(), size_t(1) << 18), [&](const tbb::blocked_range<size_t>& r) {
        std::fill(buffer_.begin() + long(r.begin()), buffer_.begin() + long(r.end()), value_);
      });
    } else {
      std::fill(buffer_.begin(), buffer_.end(), value_);
    }
  }
  const Tessellation& result() override { return empty_; }
  size_t bytes_out() const override { return buffer_.size() * sizeof(float); }

 private:
  Backend backend_;
  std::vector<float> buffer_;
  float value_ = 0;
  Tessellation empty_;
};

const char* const kCalibrationMesh = "write-64MiB";

// One benchmark of a bench run, prepared on first use so that only what the filter selects is built.
struct LazyRun {
  DescribedRun run;
  std::unique_ptr<Evaluation> eval;
  // Prepared, then executed once untimed, as measure_row does before it times: lavapipe compiles
  // a pipeline's shaders at its first dispatch (0.7 s for cpatch-2pass's evaluate pass), which
  // would otherwise land in the first round's sample.
  Evaluation* get() {
    if (!eval) {
      eval = run.scheme->prepare(*run.accepted, run.request);
      execute_on(*eval, run.request.backend);
    }
    return eval.get();
  }
};

std::unique_ptr<LazyRun> calibration_run(Backend backend) {
  auto lazy = std::make_unique<LazyRun>();
  RunRow& row = lazy->run.row;
  row.scheme = row.spec = row.role = kCalibrationScheme;
  row.backend = backend;
  row.mesh = kCalibrationMesh;
  row.message = "calibration probe: streaming store";
  lazy->run.request.backend = backend;
  lazy->eval = std::make_unique<WriteProbe>(backend);
  return lazy;
}

// Shows the rounds' progress: a terminal's status line names each benchmark as it first asks for
// its evaluation in a round; a round is one item.
class ProgressReporter : public TeeReporter {
 public:
  ProgressReporter(benchmark::BenchmarkReporter* display, Progress* progress) : TeeReporter(display), progress_(progress) {}
  void began(const std::string& name) {
    if (!progress_ || started_ == name) return;  // Google Benchmark calls a benchmark more than once
    started_ = name;
    progress_->begin(round_ + ": " + name);
  }
  void round_begins(int round, int rounds) {
    round_ = "round " + std::to_string(round + 1) + "/" + std::to_string(rounds);
    started_.clear();
  }
  void round_ends(size_t benchmarks) {
    if (progress_) progress_->done(round_, ": " + std::to_string(benchmarks) + " benchmarks timed", false);
  }

 private:
  Progress* progress_;
  std::string started_, round_;
};

std::vector<Backend> calibration_backends(const std::vector<RunSpec>& specs, const BenchRounds& how) {
  std::vector<Backend> backends;
  if (how.rounds > 0 && how.calibration)
    for (Backend b : {Backend::Cpu, Backend::CpuMt})
      if (std::any_of(specs.begin(), specs.end(), [b](const RunSpec& s) { return s.backend == b; })) backends.push_back(b);
  return backends;
}

}  // namespace

bool parse_benchmark_flags(const std::string& program, const std::vector<std::string>& flags) {
  static std::vector<std::string> args;  // Google Benchmark keeps argv[0] for its context line
  static std::vector<char*> argv;
  args = {program};
  args.insert(args.end(), flags.begin(), flags.end());
  argv.clear();
  for (auto& a : args) argv.push_back(a.data());
  int argc = static_cast<int>(argv.size());
  benchmark::Initialize(&argc, argv.data());
  return !benchmark::ReportUnrecognizedArguments(argc, argv.data());
}

benchmark::BenchmarkReporter* benchmark_console() {
  static benchmark::ConsoleReporter console;
  return &console;
}

std::vector<RunRow> bench_runs(const std::vector<RunSpec>& specs, const MeasureOptions& o, MeasureContext& ctx,
                               benchmark::BenchmarkReporter* display, const BenchRounds& how) {
  const int rounds = how.rounds;
  std::vector<std::unique_ptr<LazyRun>> runs;
  for (const RunSpec& spec : specs) {
    auto lazy = std::make_unique<LazyRun>();
    lazy->run = describe_run(spec, o, ctx);
    const RunRow& row = lazy->run.row;
    if (how.every_spec_named && row.status == RunStatus::Unsupported) throw InputError(row.name(), row.message);
    runs.push_back(std::move(lazy));
  }
  for (Backend b : calibration_backends(specs, how)) runs.push_back(calibration_run(b));
  ProgressReporter tee(rounds > 0 ? nullptr : display, rounds > 0 ? how.progress : nullptr);
  auto register_all = [&](const std::vector<size_t>& order, int repetitions) {
    for (size_t i : order) {
      LazyRun* l = runs[i].get();
      if (l->run.row.status == RunStatus::Unsupported) continue;
      const std::string name = l->run.row.name();
      auto* b = register_timing(name, [l, &tee, name] {
        tee.began(name);
        return l->get();
      }, l->run.row.backend);
      if (repetitions > 0) b->Repetitions(repetitions);
      if (how.min_time_s > 0) b->MinTime(how.min_time_s);
    }
  };
  std::vector<size_t> order(runs.size());
  std::iota(order.begin(), order.end(), size_t(0));
  if (rounds <= 0) {
    register_all(order, 0);  // repetitions and interleaving from Google Benchmark's flags
    benchmark::RunSpecifiedBenchmarks(&tee);
    benchmark::ClearRegisteredBenchmarks();
  } else {
    // Every round runs each benchmark once, in a fresh random order: sample r of a scheme and of
    // its peer are measured close in time, so the gate can pair them.
    std::mt19937 shuffle(12345);
    for (int r = 0; r < rounds; ++r) {
      tee.round_begins(r, rounds);
      std::shuffle(order.begin(), order.end(), shuffle);
      register_all(order, 1);
      const size_t timed = benchmark::RunSpecifiedBenchmarks(&tee);
      benchmark::ClearRegisteredBenchmarks();
      tee.round_ends(timed);
    }
  }
  std::vector<RunRow> rows;
  for (auto& l : runs) {
    if (!l->eval) continue;  // filtered out or unsupported
    RunRow& row = l->run.row;
    record_output(row, *l->eval);
    fill_timing(row, tee.samples[row.name()], l->eval.get(), is_gpu(row.backend), ctx.machine());
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace sdb
