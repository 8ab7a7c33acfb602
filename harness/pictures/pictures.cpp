#include "harness/pictures/pictures.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>

#include "datasets/manifest.h"
#include "harness/bench/measure.h"
#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/gpu/context.h"
#include "harness/gpu/device_info.h"
#include "harness/gpu/image.h"
#include "harness/gpu/mesh_renderer.h"
#include "harness/pictures/colour_map.h"
#include "harness/pictures/framing.h"

namespace sdb::pictures {
namespace {

namespace fs = std::filesystem;

constexpr const char* kColourBarFile = "colour-bar.png";
constexpr const char* kManifestFile = "pictures.json";
// Past this an explicit --level is refused per picture: the tessellation, its deviation and the
// upload would take minutes and gigabytes for a picture a few hundred pixels wide.
constexpr double kMaxPictureTriangles = 20e6;
// The shaded pictures' material, as MeshRenderer's default.
constexpr Point3 kMaterial{0.80f, 0.72f, 0.60f};

bool has_cpu(const SchemeInfo& info) {
  return std::find(info.backends.begin(), info.backends.end(), Backend::Cpu) != info.backends.end();
}

// File names keep letters, digits, '.', '_' and '-': "crane/spot_control" -> "crane-spot_control".
std::string file_safe(const std::string& s) {
  std::string out = s;
  for (char& c : out)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') c = '-';
  return out;
}

std::string picture_file(const std::string& scheme, const std::string& mesh, const std::string& kind) {
  return file_safe(scheme) + "_" + file_safe(mesh) + "_" + kind + ".png";
}

nlohmann::ordered_json entry_json(const PictureEntry& e) {
  nlohmann::ordered_json j{{"scheme", e.scheme}, {"mesh", e.mesh},         {"level", e.level},
                           {"backend", e.backend}, {"triangles", e.triangles}, {"kind", e.kind}};
  if (!e.file.empty()) j["file"] = e.file;
  if (e.deviation_range) j["deviation_range"] = {e.deviation_range->first, e.deviation_range->second};
  if (!e.error.empty()) j["error"] = e.error;
  return j;
}

nlohmann::ordered_json manifest_json(const PictureManifest& m) {
  nlohmann::ordered_json j{{"schema", 1}, {"available", m.available}};
  if (!m.available) j["reason"] = m.reason;
  if (!m.device.empty()) j["device"] = m.device;
  if (!m.colour_bar.empty()) j["colour_bar"] = m.colour_bar;
  j["pictures"] = nlohmann::ordered_json::array();
  for (const PictureEntry& e : m.pictures) j["pictures"].push_back(entry_json(e));
  return j;
}

// Written beside, then renamed over: a reader never sees half a manifest.
void write_manifest(const PictureManifest& m, const fs::path& dir) {
  const fs::path path = dir / kManifestFile, temporary = dir / (std::string(kManifestFile) + ".partial");
  {
    std::ofstream out(temporary);
    out << manifest_json(m).dump(2) << "\n";
    if (!out.flush()) throw InputError(temporary.string(), "cannot write the pictures manifest");
  }
  fs::rename(temporary, path);
}

struct SchemeChoice {
  ResolvedScheme resolved;
  std::string spelled;
};

// In the order given, each once: the same name twice would draw the same files twice.
std::vector<std::string> once_each(const std::vector<std::string>& names) {
  std::vector<std::string> out;
  for (const std::string& n : names)
    if (std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
  return out;
}

std::vector<SchemeChoice> resolve_schemes(const std::vector<std::string>& spelled) {
  std::vector<SchemeChoice> out;
  for (const std::string& s : once_each(spelled.empty() ? default_schemes() : spelled)) {
    SchemeChoice c{resolve_scheme(s), s};
    if (!has_cpu(c.resolved.scheme->info()))
      throw InputError(c.resolved.spec, "has no cpu backend; pictures draw the cpu backend's tessellation");
    out.push_back(std::move(c));
  }
  return out;
}

// One scheme's surface on the mesh, and its two entries as they stand.
struct Surface {
  const SchemeChoice* scheme = nullptr;
  JudgedSurfaces surfaces;  // the accepted mesh the scheme subdivides, and the input it is judged against
  std::unique_ptr<Evaluation> evaluation;  // null when tessellating failed (the entries say why)
  PictureEntry shaded, deviation;
};

// The pictures of one mesh: every scheme's surface first, then their pictures under one camera.
class MeshPictures {
 public:
  MeshPictures(const std::string& mesh, const PictureRequest& request, MeasureContext& measure, gpu::Context& gpu,
               const fs::path& dir)
      : mesh_(mesh), request_(request), measure_(measure), gpu_(gpu), dir_(dir) {}

  void draw(const std::vector<SchemeChoice>& schemes, PictureManifest& manifest, const PictureCallback& on_picture) {
    std::vector<Surface> surfaces;
    std::vector<const Tessellation*> drawn;
    for (const SchemeChoice& scheme : schemes) {
      try {
        surfaces.push_back(tessellate(scheme));
      } catch (const InputError& e) {  // the scheme does not take this mesh
        manifest.notes.push_back(e.what());
        continue;
      }
      if (surfaces.back().evaluation) drawn.push_back(&surfaces.back().evaluation->result());
    }
    std::optional<gpu::Camera> camera;
    if (!drawn.empty()) camera = picture_camera(drawn, float(request_.width) / float(request_.height));
    for (Surface& s : surfaces) {
      if (s.evaluation) {
        draw_shaded(s, *camera);
        draw_deviation(s, *camera);
        s.evaluation.reset();
      }
      for (const PictureEntry* e : {&s.shaded, &s.deviation}) {
        manifest.pictures.push_back(*e);
        if (on_picture) on_picture(*e);
      }
    }
  }

 private:
  // Throws InputError when the scheme does not take the mesh; any other failure is the entries'.
  Surface tessellate(const SchemeChoice& choice) {
    Surface s;
    s.scheme = &choice;
    s.shaded.scheme = s.deviation.scheme = choice.resolved.spec;
    s.shaded.mesh = s.deviation.mesh = mesh_;
    s.shaded.kind = "shaded";
    s.deviation.kind = "deviation";
    const Scheme& scheme = *choice.resolved.scheme;
    s.surfaces = judged_surfaces(mesh_, scheme, measure_);
    const ControlMesh& accepted = *s.surfaces.accepted;
    try {
      const Parameters& parameters = choice.resolved.parameters;
      const int level = request_.level ? *request_.level : picture_level(scheme, accepted, parameters);
      s.shaded.level = s.deviation.level = level;
      const RunRequest run{Backend::Cpu, level, 0, parameters};
      if (auto why = declined(scheme, run)) throw Unsupported(*why);
      const long estimate = scheme.estimated_triangles(accepted, run);
      if (double(estimate) > kMaxPictureTriangles)
        throw Unsupported("about " + std::to_string(estimate) + " triangles at this level, too many for a picture");
      s.evaluation = scheme.prepare(accepted, run);
      execute_on(*s.evaluation, Backend::Cpu);
      s.shaded.triangles = s.deviation.triangles = long(s.evaluation->result().num_triangles());
    } catch (const InputError&) {
      throw;  // refused late, in prepare(): the scheme does not take the mesh either
    } catch (const std::exception& e) {
      s.evaluation.reset();
      s.shaded.error = s.deviation.error = e.what();
    }
    return s;
  }

  gpu::PictureOptions options(const gpu::Camera& camera, float ambient) const {
    gpu::PictureOptions o;
    o.width = request_.width;
    o.height = request_.height;
    o.ambient = ambient;
    o.camera = camera;
    return o;
  }

  void write(PictureEntry& entry, const gpu::Image& image) {
    const std::string file = picture_file(entry.scheme, entry.mesh, entry.kind);
    gpu::write_png(image, (dir_ / file).string());
    entry.file = file;
  }

  void draw_shaded(Surface& s, const gpu::Camera& camera) {
    try {
      const Tessellation& t = s.evaluation->result();
      write(s.shaded, gpu::render_image(gpu_, t, std::vector<Point3>(t.positions.size(), kMaterial), options(camera, 0.2f)));
    } catch (const std::exception& e) {
      s.shaded.error = e.what();
    }
  }

  void draw_deviation(Surface& s, const gpu::Camera& camera) {
    try {
      // Distance from the input's limit surface over its diagonal, as the rows measure it.
      const Tessellation& t = s.evaluation->result();
      const std::vector<float> deviation = input_limit_distance(t, s.surfaces, measure_).vertex_rel_diag;
      float max = 0;  // of the finite values: a NaN takes the map's low end, as viridis() says
      for (float d : deviation)
        if (std::isfinite(d)) max = std::max(max, d);
      std::vector<Point3> colours(deviation.size());
      for (size_t i = 0; i < deviation.size(); ++i) colours[i] = viridis(max > 0 ? deviation[i] / max : 0.0f);
      s.deviation.deviation_range = {0.0, double(max)};
      write(s.deviation, gpu::render_image(gpu_, t, colours, options(camera, 0.45f)));
    } catch (const std::exception& e) {
      s.deviation.error = e.what();
    }
  }

  std::string mesh_;
  const PictureRequest& request_;
  MeasureContext& measure_;
  gpu::Context& gpu_;
  fs::path dir_;
};

fs::path make_picture_dir(const std::string& out_dir) {
  const fs::path dir = fs::path(out_dir) / "pictures";
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir.string(), "cannot create the pictures folder (" + ec.message() + ")");
  return dir;
}

}  // namespace

std::vector<std::string> default_schemes() {
  std::vector<std::string> names;
  std::vector<std::pair<std::string, SubdivisionRule>> drawn;  // paper and rule
  for (const auto& s : all_schemes()) {
    const SchemeInfo& info = s->info();
    if (info.role != SchemeRole::Method || !has_cpu(info)) continue;
    const std::pair<std::string, SubdivisionRule> key{info.paper, info.reference};
    if (std::find(drawn.begin(), drawn.end(), key) != drawn.end()) continue;
    drawn.push_back(key);
    names.push_back(info.name);
  }
  return names;
}

std::vector<std::string> default_meshes() {
  // Without the corpus, a closed genus-0 built-in with extraordinary vertices: every scheme takes it.
  const std::string real = corpus_has("crane/spot_control") ? "crane/spot_control" : "pole5";
  return {real, "frog-standin", "icosphere"};
}

int picture_level(const Scheme& scheme, const ControlMesh& accepted, const Parameters& parameters) {
  const SchemeInfo& info = scheme.info();
  constexpr double kTarget = 173e3;  // sqrt(100 k x 300 k)
  const bool rate = info.level_kind == LevelKind::Rate;
  int best = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  for (int level = rate ? 2 : 0; level <= (rate ? 1025 : 16); ++level) {
    const RunRequest run{Backend::Cpu, level, 0, parameters};
    if (declined(scheme, run)) continue;
    const double triangles = double(scheme.estimated_triangles(accepted, run));
    if (triangles <= 0) continue;
    const double distance = std::abs(std::log(triangles / kTarget));
    if (distance < best_distance) best = level, best_distance = distance;
    if (triangles > kTarget) break;
  }
  if (best >= 0) return best;
  return info.default_levels.empty() ? (rate ? 2 : 0) : info.default_levels.front();
}

PictureManifest write_pictures(const PictureRequest& request, const std::string& out_dir,
                               const PictureCallback& on_picture) {
  if (request.width < 16 || request.height < 16 || request.width > 4096 || request.height > 4096)
    throw InputError("pictures", "a picture of " + std::to_string(request.width) + " x " + std::to_string(request.height) +
                                     " pixels: each side must be 16 to 4096");
  const std::vector<SchemeChoice> schemes = resolve_schemes(request.schemes);
  const std::vector<std::string> meshes = once_each(request.meshes.empty() ? default_meshes() : request.meshes);
  MeasureContext measure{MachineInfo{}};
  for (const std::string& mesh : meshes) measure.mesh(mesh);  // InputError for a bad name, before anything is written
  const fs::path dir = make_picture_dir(out_dir);

  PictureManifest manifest;
  std::shared_ptr<gpu::Context> gpu;
  try {
    gpu = gpu::shared_context();
  } catch (const std::exception& e) {
    manifest.reason = e.what();
    write_manifest(manifest, dir);
    return manifest;
  }
  manifest.available = true;
  manifest.device = gpu::summary(gpu->info());
  gpu::write_png(colour_bar(request.width, std::max(16u, request.width / 24)), (dir / kColourBarFile).string());
  manifest.colour_bar = kColourBarFile;
  for (const std::string& mesh : meshes) MeshPictures(mesh, request, measure, *gpu, dir).draw(schemes, manifest, on_picture);
  write_manifest(manifest, dir);
  return manifest;
}

}  // namespace sdb::pictures
