#include "harness/results/results.h"

#include <nlohmann/json.hpp>

#include "harness/results/bound_judgement.h"
#include "harness/results/results_check.h"
#include "harness/results/results_json.h"

#include <fstream>
#include <limits>
#include <filesystem>
#include <cmath>
#include <cstdint>

#include "harness/core/errors.h"
#include "harness/results/run_spec.h"

namespace sdb {

using nlohmann::json;

void to_json(json& j, const TimeStats& t) {
  j = {{"median", t.median}, {"min", t.min}, {"max", t.max}, {"reps", t.reps}, {"samples", t.samples}};
}
namespace {

// JSON has no NaN or infinity; nlohmann writes them as null. So null where a number belongs reads
// back as NaN, and every reader of results (report, gate) treats NaN as "not measured".
double number(const json& j, const char* key, double fallback) {
  if (!j.contains(key)) return fallback;
  const json& v = j[key];
  return v.is_null() ? std::numeric_limits<double>::quiet_NaN() : v.get<double>();
}

// A count or index: a whole number that fits T, never a conversion out of range (undefined for a
// float such as 1e300 into an int; found by tests/fuzz). Missing or null: the fallback.
template <class T>
T whole(const json& j, const char* key, T fallback) {
  if (!j.contains(key) || j[key].is_null()) return fallback;
  const json& v = j[key];
  using limits = std::numeric_limits<T>;
  bool fits = false;
  if (v.is_number_unsigned()) fits = v.get<uint64_t>() <= uint64_t(limits::max());
  else if (v.is_number_integer()) {
    const int64_t i = v.get<int64_t>();
    fits = i < 0 ? limits::is_signed && i >= int64_t(limits::min()) : uint64_t(i) <= uint64_t(limits::max());
  } else if (v.is_number_float()) {
    const double d = v.get<double>();
    fits = std::trunc(d) == d && d >= double(limits::min()) && d < std::ldexp(1.0, limits::digits);
  } else {
    throw json::type_error::create(302, std::string("'") + key + "' must be a number, not " + v.type_name(), &j);
  }
  if (!fits) throw json::other_error::create(501, std::string("'") + key + "' is not a whole number within range: " + v.dump(), &j);
  return v.is_number_float() ? static_cast<T>(v.get<double>()) : v.get<T>();
}

}  // namespace

void from_json(const json& j, TimeStats& t) {
  if (j.is_null()) return;  // no timing: reps 0
  t.median = number(j, "median", NAN), t.min = number(j, "min", NAN), t.max = number(j, "max", NAN);
  t.reps = whole(j, "reps", 0);
  if (j.contains("samples") && !j["samples"].is_null())
    for (const json& v : j["samples"]) t.samples.push_back(v.is_null() ? NAN : v.get<double>());
}

namespace {

Backend backend_from(const json& j, const char* key) {
  const std::string s = j.at(key).get<std::string>();
  const auto b = parse_backend(s);
  if (!b) throw json::other_error::create(501, std::string("unknown backend '") + s + "' in " + key, &j);
  return *b;
}

RunStatus status_from(const json& j) {
  const std::string s = j.value("status", "ok");
  const auto st = parse_run_status(s);
  if (!st) throw json::other_error::create(501, "unknown status '" + s + "'", &j);
  return *st;
}

}  // namespace

std::string RunRow::name() const { return run_name(spelled(), backend, mesh, level); }

bool on_cpu_implementation(const MachineInfo& m, Backend backend) {
  if (backend == Backend::Vulkan) return m.vulkan_device_type == "cpu";
  if (backend == Backend::OpenGl) return m.opengl_device_type == "cpu";
  return false;
}

std::string cpu_implementation_words(const MachineInfo& m, Backend backend) {
  if (!on_cpu_implementation(m, backend)) return "";
  const bool vulkan = backend == Backend::Vulkan;
  return (vulkan ? m.vulkan_device : m.opengl_renderer) + ", a CPU implementation of " + (vulkan ? "Vulkan" : "OpenGL") +
         ", not a GPU";
}

void to_json(json& j, const RunRow& r) {
  j = {{"scheme", r.scheme},
       {"spec", r.spelled()},
       {"role", r.role},
       {"backend", to_string(r.backend)},
       {"params", r.params},
       {"peer", r.peer},
       {"device", r.device},
       {"mesh", r.mesh},
       {"mesh_faces", r.mesh_faces},
       {"mesh_vertices", r.mesh_vertices},
       {"extraordinary_fraction", r.extraordinary_fraction},
       {"level", r.level},
       {"tessellation", r.tessellation},
       {"triangles", r.triangles},
       {"vertices", r.vertices},
       {"time_ms", r.time_ms},
       {"upload_ms", r.upload_ms},
       {"readback_ms", r.readback_ms},
       {"triangle_rate_mtris", r.triangle_rate_mtris},
       {"bytes_out", r.bytes_out},
       {"bandwidth_fraction", r.bandwidth_fraction},
       {"watertight",
        {{"open_edges", r.watertight.open_edges},
         {"rays", r.watertight.rays},
         {"ray_cracks", r.watertight.ray_cracks},
         {"seed", r.watertight.seed}}},
       {"status", to_string(r.status)},
       {"message", r.message}};
  if (r.peer_backend) j["peer_backend"] = to_string(*r.peer_backend);
  if (bound_declared(r.bound))
    j["deviation_bound"] = {{"pos_rel_diag", r.bound.pos_rel_diag}, {"normal_deg", r.bound.normal_deg}};
  if (bound_declared(r.own_bound))
    j["own_deviation_bound"] = {{"pos_rel_diag", r.own_bound.pos_rel_diag}, {"normal_deg", r.own_bound.normal_deg}};
  if (!r.limit.empty()) j["limit"] = r.limit;
  if (!r.validation_of.empty()) j["validation_of"] = r.validation_of;
  if (r.gpu_time_ms) j["gpu_time_ms"] = *r.gpu_time_ms;
  if (!r.gpu_passes.empty()) {
    json passes = json::array();
    for (const auto& p : r.gpu_passes) passes.push_back({{"label", p.label}, {"ms", p.ms}});
    j["gpu_passes"] = passes;
  }
  const DeviationFigures& d = r.deviation;
  if (d.measured) {
    j["deviation"] = {{"pos_max_pct", d.pos_max_pct},       {"pos_mean_pct", d.pos_mean_pct},
                      {"pos_rms_pct", d.pos_rms_pct},       {"pos_p95_pct", d.pos_p95_pct},
                      {"pos_max_rel_diag", d.pos_max_rel_diag}, {"normal_max_deg", d.normal_max_deg},
                      {"normal_mean_deg", d.normal_mean_deg},   {"hausdorff_rel", d.hausdorff_rel},
                      {"pos_p95_rel_diag", d.pos_p95_rel_diag},   {"measured_by", d.measured_by}};
    if (d.own)
      j["deviation"]["own_reference"] = {{"pos_max_rel_diag", d.own->pos_max_rel_diag},
                                         {"pos_p95_rel_diag", d.own->pos_p95_rel_diag},
                                         {"pos_max_pct", d.own->pos_max_pct},
                                         {"pos_p95_pct", d.own->pos_p95_pct},
                                         {"normal_max_deg", d.own->normal_max_deg}};
    if (d.normals_undefined > 0) j["deviation"]["normals_undefined"] = d.normals_undefined;
  } else if (d.hausdorff_rel >= 0) {
    // No SurfaceCoords: the distance to the limit at the same point is not defined, Hausdorff is.
    j["deviation"] = {{"pos_max_pct", nullptr},  {"pos_mean_pct", nullptr},   {"pos_rms_pct", nullptr},
                      {"pos_p95_pct", nullptr},  {"pos_max_rel_diag", nullptr}, {"normal_max_deg", nullptr},
                      {"normal_mean_deg", nullptr}, {"hausdorff_rel", d.hausdorff_rel}};
  } else {
    j["deviation"] = nullptr;
  }
}

void from_json(const json& j, RunRow& r) {
  r.scheme = j.at("scheme"), r.backend = backend_from(j, "backend"), r.device = j.value("device", "");
  r.spec = j.value("spec", r.scheme), r.role = j.value("role", "");
  r.params = j.value("params", std::map<std::string, double>{});
  r.peer = j.value("peer", "");
  if (j.contains("peer_backend")) r.peer_backend = backend_from(j, "peer_backend");
  if (j.contains("deviation_bound")) {
    r.bound.pos_rel_diag = j["deviation_bound"].value("pos_rel_diag", -1.0);
    r.bound.normal_deg = j["deviation_bound"].value("normal_deg", -1.0);
  }
  if (j.contains("own_deviation_bound")) {
    r.own_bound.pos_rel_diag = j["own_deviation_bound"].value("pos_rel_diag", -1.0);
    r.own_bound.normal_deg = j["own_deviation_bound"].value("normal_deg", -1.0);
  }
  r.limit = j.value("limit", "");
  r.validation_of = j.value("validation_of", "");
  r.mesh = j.at("mesh");
  r.mesh_faces = whole(j, "mesh_faces", 0), r.mesh_vertices = whole(j, "mesh_vertices", 0);
  r.extraordinary_fraction = number(j, "extraordinary_fraction", 0.0);
  (void)j.at("level");  // required: throws when missing
  r.level = whole(j, "level", 0), r.tessellation = whole(j, "tessellation", 0);
  r.triangles = whole(j, "triangles", 0L), r.vertices = whole(j, "vertices", 0L);
  r.time_ms = j.value("time_ms", json()).get<TimeStats>();
  if (j.contains("gpu_time_ms")) r.gpu_time_ms = j["gpu_time_ms"].get<TimeStats>();
  r.upload_ms = number(j, "upload_ms", 0.0), r.readback_ms = number(j, "readback_ms", 0.0);
  if (j.contains("gpu_passes"))
    for (const auto& p : j["gpu_passes"]) r.gpu_passes.push_back({p.at("label"), p.at("ms")});
  r.triangle_rate_mtris = number(j, "triangle_rate_mtris", 0.0);
  r.bytes_out = whole(j, "bytes_out", 0L);
  r.bandwidth_fraction = number(j, "bandwidth_fraction", 0.0);
  if (j.contains("watertight")) {
    const json& w = j["watertight"];
    r.watertight = {whole(w, "open_edges", -1L), whole(w, "rays", 0L), whole(w, "ray_cracks", -1L), whole(w, "seed", uint64_t(0))};
  }
  if (j.contains("deviation") && !j["deviation"].is_null()) {
    const json& d = j["deviation"];
    // Hausdorff-only rows (no SurfaceCoords) have every per-vertex figure null; a measured row
    // keeps its finite figures beside the ones that were NaN.
    r.deviation.measured = false;
    for (const char* key : {"pos_max_pct", "pos_mean_pct", "pos_rms_pct", "pos_p95_pct", "pos_max_rel_diag", "normal_max_deg",
                            "normal_mean_deg"})
      r.deviation.measured |= d.contains(key) && !d[key].is_null();
    r.deviation.hausdorff_rel = number(d, "hausdorff_rel", -1.0);
    if (r.deviation.measured) {
      r.deviation.pos_max_pct = number(d, "pos_max_pct", 0.0), r.deviation.pos_mean_pct = number(d, "pos_mean_pct", 0.0);
      r.deviation.pos_rms_pct = number(d, "pos_rms_pct", 0.0), r.deviation.pos_p95_pct = number(d, "pos_p95_pct", 0.0);
      r.deviation.pos_max_rel_diag = number(d, "pos_max_rel_diag", 0.0);
      r.deviation.normal_max_deg = number(d, "normal_max_deg", 0.0);
      r.deviation.normal_mean_deg = number(d, "normal_mean_deg", 0.0);
      r.deviation.normals_undefined = whole(d, "normals_undefined", 0L);
      r.deviation.pos_p95_rel_diag = number(d, "pos_p95_rel_diag", NAN);
      r.deviation.measured_by = d.value("measured_by", "");
      if (d.contains("own_reference") && d["own_reference"].is_object()) {
        const json& o = d["own_reference"];
        r.deviation.own = DeviationFigures::Own{number(o, "pos_max_rel_diag", NAN), number(o, "pos_p95_rel_diag", NAN),
                                                number(o, "pos_max_pct", NAN), number(o, "pos_p95_pct", NAN),
                                                number(o, "normal_max_deg", NAN)};
      }
    }
  }
  r.status = status_from(j), r.message = j.value("message", "");
}

void to_json(json& j, const MachineInfo& m) {
  j = {{"cpu_model", m.cpu_model},       {"cores", m.cores},
       {"memory_gib", m.memory_gib},     {"vulkan_device", m.vulkan_device},
       {"vulkan_device_type", m.vulkan_device_type}, {"vulkan_memory_gib", m.vulkan_memory_gib},
       {"opengl_device_type", m.opengl_device_type},
       {"opengl_renderer", m.opengl_renderer}, {"opengl_version", m.opengl_version},
       {"vulkan_driver", m.vulkan_driver}, {"vulkan_api", m.vulkan_api},
       {"compiler", m.compiler},         {"build_type", m.build_type},
       {"git_commit", m.git_commit},     {"write_bandwidth_gbs", m.write_bandwidth_gbs},
       {"write_bandwidth_mt_gbs", m.write_bandwidth_mt_gbs}, {"gpu_write_bandwidth_gbs", m.gpu_write_bandwidth_gbs},
       {"gpu_shader_write_bandwidth_gbs", m.gpu_shader_write_bandwidth_gbs}};
  if (!m.probes_from.empty()) j["probes_from"] = m.probes_from;
}
void from_json(const json& j, MachineInfo& m) {
  m.cpu_model = j.value("cpu_model", ""), m.cores = whole(j, "cores", 0), m.memory_gib = number(j, "memory_gib", 0.0);
  m.vulkan_device = j.value("vulkan_device", ""), m.vulkan_driver = j.value("vulkan_driver", "");
  m.vulkan_api = j.value("vulkan_api", "");
  m.vulkan_device_type = j.value("vulkan_device_type", ""), m.vulkan_memory_gib = number(j, "vulkan_memory_gib", 0.0);
  m.opengl_device_type = j.value("opengl_device_type", "");
  m.opengl_renderer = j.value("opengl_renderer", ""), m.opengl_version = j.value("opengl_version", "");
  m.compiler = j.value("compiler", ""), m.build_type = j.value("build_type", ""), m.git_commit = j.value("git_commit", "");
  m.write_bandwidth_gbs = number(j, "write_bandwidth_gbs", 0.0);
  m.write_bandwidth_mt_gbs = number(j, "write_bandwidth_mt_gbs", 0.0);
  m.gpu_write_bandwidth_gbs = number(j, "gpu_write_bandwidth_gbs", 0.0);
  m.gpu_shader_write_bandwidth_gbs = number(j, "gpu_shader_write_bandwidth_gbs", 0.0);
  m.probes_from = j.value("probes_from", "");
}

namespace {

json paired_json(const PairedCell& c) {
  return {{"mesh", c.mesh},
          {"scheme", c.row.scheme},
          {"backend", to_string(c.row.backend)},
          {"level", c.row.level},
          {"triangles", c.row.triangles},
          {"peer",
           {{"scheme", c.peer.scheme}, {"backend", to_string(c.peer.backend)}, {"level", c.peer.level}, {"triangles", c.peer.triangles}}},
          {"rounds", c.rounds},
          {"rate_ratio",
           {{"median", c.rate_ratio_median}, {"min", c.rate_ratio_min}, {"max", c.rate_ratio_max}, {"per_round", c.rate_ratio_per_round}}},
          {"time_ms", {{"median", c.time_ms_median}}},
          {"peer_time_ms", {{"median", c.peer_time_ms_median}}}};
}

PairedCell paired_from(const json& j) {
  PairedCell c;
  c.mesh = j.at("mesh");
  c.row = {j.at("scheme"), backend_from(j, "backend"), whole(j, "level", 0), whole(j, "triangles", 0L)};
  const json& p = j.at("peer");
  c.peer = {p.at("scheme"), backend_from(p, "backend"), whole(p, "level", 0), whole(p, "triangles", 0L)};
  c.rounds = whole(j, "rounds", 0);
  const json& r = j.at("rate_ratio");
  c.rate_ratio_median = number(r, "median", NAN), c.rate_ratio_min = number(r, "min", NAN), c.rate_ratio_max = number(r, "max", NAN);
  if (r.contains("per_round") && !r["per_round"].is_null())
    for (const json& v : r["per_round"]) c.rate_ratio_per_round.push_back(v.is_null() ? NAN : v.get<double>());
  c.time_ms_median = j.contains("time_ms") ? number(j["time_ms"], "median", NAN) : NAN;
  c.peer_time_ms_median = j.contains("peer_time_ms") ? number(j["peer_time_ms"], "median", NAN) : NAN;
  return c;
}

std::optional<ShardInfo> shard_from(const json& j) {
  if (!j.contains("shard") || j["shard"].is_null()) return std::nullopt;
  const ShardInfo s{whole(j["shard"], "index", -1), whole(j["shard"], "count", 0)};
  if (s.count < 1 || s.index < 0 || s.index >= s.count)
    throw json::other_error::create(501, "'shard' must have 0 <= index < count: " + j["shard"].dump(), &j);
  return s;
}

}  // namespace

void prepare_output_folder(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!std::filesystem::is_directory(dir))
    throw InputError(dir, std::filesystem::exists(dir) ? "is a file, not a folder for the results"
                                                       : "cannot create the output folder: " + ec.message());
  const std::filesystem::path probe = std::filesystem::path(dir) / ".subdivbench-write-test";
  {
    std::ofstream out(probe);
    if (!out) throw InputError(dir, "output folder is not writable");
  }
  std::filesystem::remove(probe, ec);
}

std::string one_line(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }

std::string row_json(const RunRow& row, int indent) {
  return indent < 0 ? one_line(row) : json(row).dump(indent, ' ', false, json::error_handler_t::replace);
}

void write_results(const ResultsFile& r, const std::string& path) {
  json j = {{"schema", r.schema}, {"machine", r.machine}, {"created", r.created}, {"rounds", r.rounds}, {"runs", r.runs}};
  if (r.shard) j["shard"] = {{"index", r.shard->index}, {"count", r.shard->count}};
  if (!r.paired.empty()) {
    j["paired"] = json::array();
    for (const PairedCell& c : r.paired) j["paired"].push_back(paired_json(c));
  }
  const std::string tmp = path + ".partial";
  {
    std::ofstream out(tmp);
    if (!out) throw InputError(path, "cannot write results");
    out << j.dump(2, ' ', false, json::error_handler_t::replace) << "\n";
    if (!out) throw InputError(path, "write failed");
  }
  // Written whole or not at all: a crash never leaves a partial file under the real name.
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw InputError(path, "cannot write results (is it a folder?)");
  }
}

ResultsFile read_results(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, "is a directory, not a results file");
  if (!std::filesystem::exists(path, ec)) throw InputError(path, "no such file");
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open results file");
  json j;
  try {
    in >> j;
  } catch (const json::exception& e) {  // parse_error, and out_of_range for a number past double's range
    throw InputError(path, std::string("malformed JSON: ") + e.what());
  }
  if (!j.is_object() || !j.contains("schema") || !j["schema"].is_number_integer())
    throw InputError(path, "not a subdivbench results file (no integer 'schema')");
  if (j["schema"] != kResultsSchema)
    throw InputError(path, "unknown results schema " + j["schema"].dump() + " (this build reads " +
                               std::to_string(kResultsSchema) + ")");
  ResultsFile r;
  try {
    r.schema = j["schema"];
    r.machine = j.value("machine", json::object()).get<MachineInfo>();
    r.created = j.value("created", "");
    r.rounds = whole(j, "rounds", 0);
    r.runs = j.at("runs").get<std::vector<RunRow>>();
    r.shard = shard_from(j);
    if (j.contains("paired") && !j["paired"].is_null())
      for (const json& c : j["paired"]) r.paired.push_back(paired_from(c));
  } catch (const json::exception& e) {
    throw InputError(path, std::string("malformed results: ") + e.what());
  }
  check_results(r, path, j.contains("machine") && j["machine"].is_object());
  return r;
}

bool is_backend_cell(const PairedCell& c) { return c.peer.scheme == c.row.scheme && c.peer.backend != c.row.backend; }

const RunRow* same_run_on(const RunRow& row, Backend backend, const std::vector<RunRow>& runs) {
  for (const RunRow& r : runs)
    if (r.status == RunStatus::Ok && r.backend == backend && r.mesh == row.mesh && r.level == row.level &&
        r.spelled() == row.spelled())
      return &r;
  return nullptr;
}

}  // namespace sdb
