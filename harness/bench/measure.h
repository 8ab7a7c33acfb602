// One measured run: a (scheme, backend, mesh, level) prepared once, validated once outside the
// timed loop, then timed by Google Benchmark. Produces a results.json row.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "harness/bench/machine.h"
#include "harness/bench/shared_validation.h"
#include "harness/core/registry.h"
#include "harness/core/scheme.h"
#include "harness/mesh/facts.h"
#include "harness/mesh/placement.h"
#include "harness/reference/dense_limit.h"
#include "harness/reference/limit_evaluator.h"
#include "harness/results/results.h"
#include "harness/results/run_spec.h"
#include "harness/validate/limit_distance.h"
#include "harness/validate/limit_projector.h"

namespace benchmark {
class BenchmarkReporter;  // Google Benchmark's, seen by measure.cpp only: bench_runs' display
}  // namespace benchmark

namespace sdb {

// Why a request does not run: the scheme's own reason (Scheme::unsupported), else a backend it
// does not declare; nullopt when it runs.
std::optional<std::string> declined(const Scheme& scheme, const RunRequest& request);

// The backend a row on `backend` reads its peer's row from: the same one where the peer has it,
// else the peer's last (fastest) CPU backend; nullopt without a peer.
std::optional<Backend> peer_backend_for(const SchemeInfo& info, Backend backend);

struct MeasureOptions {
  int reps = 5;
  double min_time_s = 0.05;  // per repetition
  bool time = true;          // false: record the one validated execution instead of benchmarking
  bool validate = true;
  bool hausdorff = true;
  // With hausdorff: only on rows without SurfaceCoords on the input, measured by nearest points,
  // where it adds the other direction (the input's surface to the output's: what a fitted surface
  // rounds off). The quick set: elsewhere the per-vertex deviation is there, and the dense
  // reference's queries cost more than the rest of a row's validation.
  bool hausdorff_only_without_coords = false;
  // False: leave out the deviation from the input's limit where the row's bound does not judge it
  // (its verdict is the same without it): a scheme with no bound there and no coords on the input
  // costs a LimitProjector of about a million triangles. The corpus scale-invariance test.
  bool unjudged_deviation = true;
  long rays = 100000;  // random lines; as many again aimed at base-face borders
  uint64_t seed = 1;
  int threads = 0;  // cpu-mt
  std::string deviation_ply;  // when set: per-vertex deviation of the output written there
  // Default sets: a scheme refusing a mesh late (in prepare) gives an "unsupported" row instead
  // of stopping the run. Explicit requests keep the InputError (exit code 2).
  bool refusals_as_rows = false;
  // Called as measure_run enters each stage ("prepare", "execute", "validate", "time") with the
  // row as it stands: a worker reports them so that a crash is named with its stage (row_worker.h).
  std::function<void(const char* stage, const RunRow& row)> on_stage;
};

// Meshes, accepted meshes and reference surfaces shared by the rows of one run.
class MeasureContext {
 public:
  explicit MeasureContext(MachineInfo machine) : machine_(std::move(machine)) {}
  // The mesh as every run takes it: placed at the origin at unit size (placement.h), its
  // geometry checked. InputError for a mesh that cannot be read or judged.
  const ControlMesh& mesh(const std::string& name);
  // The same mesh, shared: the input whose limit surface rows are judged against.
  std::shared_ptr<const ControlMesh> input(const std::string& name);
  // Where the mesh named `name` was moved from: outputs written for the user map back with it.
  Placement placement(const std::string& name);
  // The mesh as the scheme takes it (quadrangulated when it asks); throws InputError if refused.
  std::shared_ptr<const ControlMesh> accepted(const std::string& name, const Scheme& scheme);
  // compute_facts of a mesh, once per content: every scheme's run read the facts of the same input
  // and accepted meshes three times (on the 22k-quad sword, facts' fans and edge tables were 14% of
  // the scale-invariance test's profile).
  const MeshFacts& facts(const ControlMesh& mesh);
  const LimitEvaluator& reference(const std::shared_ptr<const ControlMesh>& mesh, SubdivisionRule rule);
  // Closest points of the same limit, for outputs with no SurfaceCoords on the mesh; built once
  // per mesh and rule.
  const LimitProjector& projector(const std::shared_ptr<const ControlMesh>& mesh, SubdivisionRule rule);
  // A dense tessellation of the same limit and its Embree scene, for Hausdorff distances; built
  // once per mesh and rule.
  const DenseLimit& dense_reference(const std::shared_ptr<const ControlMesh>& mesh, SubdivisionRule rule);
  // Outputs validated by this context's rows, whose verdicts a row with the same bytes takes
  // (shared_validation.h).
  ValidatedOutputs& validated_outputs() { return validated_; }
  const MachineInfo& machine() const { return machine_; }
  // The bandwidth probes, taken once the selection is known to be good (machine.h), unless the
  // machine block came with them (probes_from); kept for the next process where it asks.
  void probe_bandwidth() {
    if (!machine_.probes_from.empty()) return;
    add_bandwidth_probes(machine_);
    keep_machine_probes(machine_);
  }

 private:
  MachineInfo machine_;
  std::map<std::string, ControlMesh> meshes_;
  std::map<std::string, std::shared_ptr<const ControlMesh>> inputs_;
  std::map<std::string, Placement> placements_;
  std::map<std::string, std::shared_ptr<const ControlMesh>> accepted_;
  // Keyed by the mesh's content, not its address: a geometry image hands every run a new g0
  // object, and caching those by address kept a 200 MB dense reference per run (the default
  // run reached 24 GB and was killed).
  std::map<size_t, MeshFacts> facts_;
  std::map<std::pair<size_t, int>, std::unique_ptr<LimitEvaluator>> references_;
  std::map<std::pair<size_t, int>, DenseLimit> dense_;
  std::map<std::pair<size_t, int>, std::unique_ptr<LimitProjector>> projectors_;
  std::vector<std::shared_ptr<const ControlMesh>> keep_alive_;  // meshes the caches point at
  ValidatedOutputs validated_;
};

// Evaluation::execute() as a backend means it: on `cpu`, inside a one-thread TBB arena.
void execute_on(Evaluation& e, Backend backend);

// What a row records before its mesh is read: the run, its device and its scheme's policy (peer,
// bound, parameters). InputError for an unknown scheme or a bad parameter.
RunRow describe_spec(const RunSpec& spec, const MachineInfo& machine);

// Runs one spec start to finish. Throws InputError when the mesh is refused or the spec unknown;
// returns a row with status "unsupported" when the scheme declines the backend or level, or runs
// into a device or size limit (Unsupported), and "failed" when a check fails (an open edge or a ray
// crack on a closed input, a deviation past the scheme's declared bound).
RunRow measure_run(const RunSpec& spec, const MeasureOptions& options, MeasureContext& context);

class Progress;

// How bench_runs measures: in Google Benchmark's way (its flags), or in paired rounds.
struct BenchRounds {
  // 0: repetitions and random interleaving from the flags. > 0: that many rounds, each running
  // every benchmark once in a fresh random order, so that sample r of every row was measured in
  // round r (the gate and run's paired figures pair them).
  int rounds = 0;
  double min_time_s = 0;     // > 0: each benchmark's time per round; 0: the flag's
  bool calibration = true;   // rounds: the write probe's rows beside the schemes' (the gate's unit)
  Progress* progress = nullptr;  // rounds: one item per round
  // Every spec was named on its own (bench --run): one the harness refuses up front (a size
  // limit, a backend the scheme declines) is an InputError naming its reason before anything is
  // measured, not a row missing after minutes of the others'.
  bool every_spec_named = false;
};

// Registers every spec with Google Benchmark (prepared lazily on first use) and runs them under
// the flags benchmark::Initialize parsed (filter, min time) and `how`. Rows carry timing only;
// `display` (may be null) shows flag-mode runs.
std::vector<RunRow> bench_runs(const std::vector<RunSpec>& specs, const MeasureOptions& options,
                               MeasureContext& context, benchmark::BenchmarkReporter* display, const BenchRounds& how = {});

// Google Benchmark's own flags for bench_runs (--benchmark_filter=..., --benchmark_min_time=...),
// given to benchmark::Initialize with `program` as their argv[0] (kept for the process's life, as
// Google Benchmark keeps it). False when one of them is not Google Benchmark's: it has said which.
bool parse_benchmark_flags(const std::string& program, const std::vector<std::string>& flags);
// Google Benchmark's console display for bench_runs' flag mode (`subdivbench bench`), one per process.
benchmark::BenchmarkReporter* benchmark_console();

// Sees every measure_run of this thread begin and end while it lives: how `paper` shows the
// progress of tables that measure their cells with measure_run (only the table knows how many).
class MeasureObserver {
 public:
  MeasureObserver(std::function<void(const RunSpec&)> began, std::function<void(const RunRow&)> ended);
  ~MeasureObserver();
  MeasureObserver(const MeasureObserver&) = delete;
  MeasureObserver& operator=(const MeasureObserver&) = delete;

  std::function<void(const RunSpec&)> began;
  std::function<void(const RunRow&)> ended;

 private:
  MeasureObserver* outer_;
};

// The surfaces a run's output is judged against (ARCHITECTURE.md: the reference is the limit
// surface of the mesh the user gave).
struct JudgedSurfaces {
  std::shared_ptr<const ControlMesh> input;     // the mesh as the user gave it
  std::shared_ptr<const ControlMesh> accepted;  // as the scheme took it: its SurfaceCoords refer to it
  // False where taking it changed the limit surface (faces of more than four sides split for
  // mipgh-quadtri); quadrangulation by a Catmull-Clark step keeps it.
  bool accepted_keeps_limit = true;
  SubdivisionRule rule = SubdivisionRule::CatmullClark;  // the scheme's (SchemeInfo::reference)
};

// False where accept_mesh changed the limit surface: faces of more than four sides split (mipgh-quadtri).
bool accepted_keeps_limit(const ControlMesh& accepted);

// The surfaces a run of `scheme` on `mesh` is judged against. InputError when the scheme refuses the mesh.
JudgedSurfaces judged_surfaces(const std::string& mesh, const Scheme& scheme, MeasureContext& context);

// The output's distance from the input's limit surface, as rows and pictures report it: at its
// SurfaceCoords where they are on the accepted mesh and that mesh has the input's limit, else by
// nearest points from every vertex to the input's limit (a scheme that subdivides a control mesh
// of its own, Tessellation::reference; one without coords). Throws Unsupported where the
// yardstick cannot be built.
LimitDistance input_limit_distance(const Tessellation& t, const JudgedSurfaces& surfaces, MeasureContext& context);

// Validation only (exact weld, rays, deviation, Hausdorff) of one evaluation's output: every
// figure against the input's limit surface (input_limit_distance), and where the scheme names a
// control mesh of its own (Tessellation::reference), its distance from that mesh's limit at its
// coords as the second figure (deviation.own).
void validate_into(RunRow& row, const Tessellation& t, const JudgedSurfaces& surfaces, const MeasureOptions& options,
                   MeasureContext& context);

// validate_into once per output content: where an earlier row of this context, of the same scheme,
// mesh, level and bounds, wrote the same bytes (compared byte for byte), the row takes its verdict
// and names it in validation_of; otherwise the output is validated and kept for the rows after it.
// Never shared where a deviation PLY is written (one per row).
void validate_once(RunRow& row, const Tessellation& t, const JudgedSurfaces& surfaces, const MeasureOptions& options,
                   MeasureContext& context);

}  // namespace sdb
