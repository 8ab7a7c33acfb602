// results.json: the contract between runs, reports, the gate and paper tables (ARCHITECTURE.md).
#pragma once

#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/backend.h"
#include "harness/core/run_status.h"
#include "harness/core/scheme.h"

namespace sdb {

inline constexpr int kResultsSchema = 1;

// The scheme of the calibration probe's rows (bench --rounds): the gate's unit for rows without a peer.
inline constexpr const char* kCalibrationScheme = "calibration";

struct TimeStats {
  double median = 0, min = 0, max = 0;
  int reps = 0;
  std::vector<double> samples;  // one per repetition, in run order (the gate's U test reads these)
};

struct WatertightFigures {
  long open_edges = -1;  // -1: not checked
  long rays = 0;
  long ray_cracks = -1;  // -1: not checked (open surfaces have no parity argument)
  uint64_t seed = 0;
};

// Against the limit surface of the row's input: at each vertex's SurfaceCoord, or by nearest
// points where the scheme's vertices have no coords on the input (measured_by says which).
struct DeviationFigures {
  bool measured = false;
  double pos_max_pct = 0, pos_mean_pct = 0, pos_rms_pct = 0, pos_p95_pct = 0;
  double pos_max_rel_diag = 0;
  double normal_max_deg = 0, normal_mean_deg = 0;
  double hausdorff_rel = -1;  // -1: not measured
  // Vertices whose normal was not compared: the limit has none there (the yardstick says so: a
  // valence-2 vertex, a ring that turns over, a face degenerate to a curve); counted, not hidden.
  long normals_undefined = 0;
  double pos_p95_rel_diag = NAN;  // NaN: not measured (files written before it)
  std::string measured_by;  // "surface-coords" | "nearest-point"; "" in files written before it
  // Against the limit of the scheme's own control mesh at its coords (Tessellation::reference:
  // a fitted geometry image's g0), the second figure; judged by the scheme's own_bound.
  struct Own {
    double pos_max_rel_diag = 0, pos_p95_rel_diag = 0, pos_max_pct = 0, pos_p95_pct = 0, normal_max_deg = 0;
  };
  std::optional<Own> own;
};

struct RunRow {
  std::string scheme;  // the registered name
  std::string spec;    // the scheme as spelled with its non-default parameters (= scheme without)
  std::string role;    // "method" | "peer" | "test" | "calibration"
  Backend backend = Backend::Cpu;
  std::string device, mesh;
  std::map<std::string, double> params;  // every parameter the scheme declares, as used
  // The row this one is read against (SchemeInfo::peer): same mesh and tessellation, this backend.
  std::string peer;
  std::optional<Backend> peer_backend;
  DeviationBound bound;  // the bound the row is judged by: its scheme's, none where the row approximates by condition
  DeviationBound own_bound;  // the scheme's bound against its own control mesh (deviation.own)
  std::string limit;  // "reproduces" | "approximates" (SchemeInfo::limit for this run); "" in older files
  int mesh_faces = 0, mesh_vertices = 0;
  double extraordinary_fraction = 0;
  int level = 0;
  int tessellation = 0;  // segments per base-face edge the level stands for
  long triangles = 0, vertices = 0;
  TimeStats time_ms;                     // wall time of Evaluation::execute()
  std::optional<TimeStats> gpu_time_ms;  // vulkan: kernel time from timestamp queries
  double upload_ms = 0, readback_ms = 0;
  std::vector<GpuPassTime> gpu_passes;
  double triangle_rate_mtris = 0;  // from the median time (GPU time for vulkan)
  long bytes_out = 0;
  double bandwidth_fraction = 0;  // rate x bytes per triangle / the machine's write bandwidth
  WatertightFigures watertight;
  DeviationFigures deviation;
  RunStatus status = RunStatus::Ok;
  std::string message;
  // The row whose validation (watertight, deviation, and the verdict of both) this one shares: an
  // earlier row of the same scheme, mesh and level whose output was the same bytes, compared byte
  // for byte (measure.h, MeasureContext::validated_output). Empty: validated on its own output.
  std::string validation_of;
  std::string name() const;  // spec/backend/mesh/level (run_spec.h)
  // The scheme as spelled: spec, or the registered name where a row (an older file) has none.
  const std::string& spelled() const { return spec.empty() ? scheme : spec; }
};

struct MachineInfo {
  std::string cpu_model;
  int cores = 0;
  double memory_gib = 0;
  std::string vulkan_device, vulkan_driver, vulkan_api;
  // Vulkan's own device type ("discrete", "integrated", "virtual", "cpu", "other"; "cpu" is Mesa's
  // lavapipe, a CPU implementation of Vulkan) and its largest device-local heap; "" and 0 in files
  // written before them.
  std::string vulkan_device_type;
  double vulkan_memory_gib = 0;
  std::string opengl_renderer, opengl_version;  // the opengl backend's context (EGL)
  std::string opengl_device_type;  // "cpu" for Mesa's software rasterizers (llvmpipe), else "gpu"; "" unknown
  std::string compiler, build_type, git_commit;
  double write_bandwidth_gbs = 0;     // one thread, streaming store
  double write_bandwidth_mt_gbs = 0;  // all threads
  double gpu_write_bandwidth_gbs = 0;  // the Vulkan device: a buffer fill timed by timestamps
  double gpu_shader_write_bandwidth_gbs = 0;  // and a compute shader that only stores (vec4s)
  // The file the probes above were read from (bench --machine-from, or a probe file reused by
  // ctest's processes: harness/bench/machine.h); "" (and absent from the file) where this
  // process measured them.
  std::string probes_from;
};

// Which part of a sharded selection a file holds (`run --shard I/N`): the rows whose sorted
// position p has p % count == index.
struct ShardInfo {
  int index = 0;  // 0-based
  int count = 1;
};

// One side of a paired summary cell: a row of the same run, named by its parts.
struct PairedSide {
  std::string scheme;  // the spec, as in rows
  Backend backend = Backend::Cpu;
  int level = 0;
  long triangles = 0;
};

// A summary cell measured in paired rounds: the scheme's row and its peer's, interleaved, so that
// both see the same machine state in each round and their ratio is not one row's noise.
struct PairedCell {
  std::string mesh;
  PairedSide row, peer;
  int rounds = 0;
  // Per round: (row triangles / row time) / (peer triangles / peer time); > 1: the scheme is faster.
  std::vector<double> rate_ratio_per_round;
  double rate_ratio_median = 0, rate_ratio_min = 0, rate_ratio_max = 0;
  double time_ms_median = 0, peer_time_ms_median = 0;
};

// A backend cell (paired.h): the peer side is the row's own scheme on the CPU, not its peer.
bool is_backend_cell(const PairedCell& c);

// The summary cell's size: the level nearest a million output triangles, which `run` pairs
// (paired.h) and the report reads; its band, within a factor of two of it, is where a quick
// mesh's cell must land (plan.h).
inline constexpr long kSummaryTriangles = 1'000'000;
inline constexpr long kSummaryLow = kSummaryTriangles / 2, kSummaryHigh = kSummaryTriangles * 2;

// Whether `backend`'s rows ran on a CPU implementation of the GPU API (lavapipe, llvmpipe): such rows
// test the device paths' correctness, their rates are not GPU figures.
bool on_cpu_implementation(const MachineInfo& m, Backend backend);
// "llvmpipe (LLVM 15.0.6, 256 bits), a CPU implementation of Vulkan, not a GPU" for such a backend, else "".
std::string cpu_implementation_words(const MachineInfo& m, Backend backend);

struct ResultsFile {
  int schema = kResultsSchema;
  // > 0: written by `bench --rounds`; sample r of every row was measured in round r.
  int rounds = 0;
  MachineInfo machine;
  std::string created;  // ISO 8601, UTC
  std::vector<RunRow> runs;
  std::optional<ShardInfo> shard;  // written by `run --shard I/N`
  std::vector<PairedCell> paired;  // absent in the file when empty
};

// The row of `runs` that measured the same scheme as spelled, mesh and level as `row` on
// `backend`, with status ok, or none: a GPU row's own cpu-mt row (paired.h's backend cells), a
// gate normaliser's unit (gate.h).
const RunRow* same_run_on(const RunRow& row, Backend backend, const std::vector<RunRow>& runs);

std::string row_json(const RunRow& row, int indent = 2);  // indent < 0: one line
void write_results(const ResultsFile& results, const std::string& path);
// Creates `dir` if needed and checks it can be written, so a bad --out fails before any measuring.
void prepare_output_folder(const std::string& dir);
// Throws InputError for unreadable files, malformed JSON or an unknown schema.
ResultsFile read_results(const std::string& path);

}  // namespace sdb
