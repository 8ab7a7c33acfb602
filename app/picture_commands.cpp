// pictures: a thin wrapper over harness/pictures (write_pictures), with a line per picture.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "app/commands.h"
#include "harness/gpu/context.h"
#include "harness/pictures/pictures.h"

namespace sdb::app {
namespace {

struct PictureVerbOptions {
  std::string out;
  std::vector<std::string> schemes, meshes;
  std::optional<int> level;
  uint32_t width = 640, height = 480;
};

void print_entry(const pictures::PictureEntry& e) {
  std::printf("%-16s %-22s level %-4d %9ld tris  %-9s  ", e.scheme.c_str(), e.mesh.c_str(), e.level, e.triangles,
              e.kind.c_str());
  if (!e.error.empty()) std::printf("FAILED: %s\n", e.error.c_str());
  else if (e.deviation_range) std::printf("%s (0 .. %.3g of the diagonal)\n", e.file.c_str(), e.deviation_range->second);
  else std::printf("%s\n", e.file.c_str());
  std::fflush(stdout);
}

int pictures_cmd(const PictureVerbOptions& opts) {
  pictures::PictureRequest request;
  request.schemes = opts.schemes;
  request.meshes = opts.meshes;
  request.level = opts.level;
  request.width = opts.width;
  request.height = opts.height;
  const auto start = std::chrono::steady_clock::now();
  const pictures::PictureManifest m = pictures::write_pictures(request, opts.out, print_entry);
  gpu::release_shared_context();
  const std::string manifest = (std::filesystem::path(opts.out) / "pictures" / "pictures.json").string();
  if (!m.available) {
    std::printf("no pictures: %s\nwrote %s\n", m.reason.c_str(), manifest.c_str());
    return 0;
  }
  for (const std::string& note : m.notes) std::printf("note: %s\n", note.c_str());
  size_t failed = 0;
  for (const auto& e : m.pictures) failed += !e.error.empty();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%zu pictures (%zu failed) on %s in %.1f s\nwrote %s\n", m.pictures.size() - failed, failed,
              m.device.c_str(), seconds, manifest.c_str());
  return 0;
}

}  // namespace

void add_picture_verbs(CLI::App& app, Verbs& verbs) {
  auto opts = std::make_shared<PictureVerbOptions>();
  auto* p = app.add_subcommand("pictures",
                               "Render each paper scheme's surface, shaded and coloured by its deviation from the "
                               "limit, into DIR/pictures (PNG files and pictures.json)");
  p->add_option("--out", opts->out, "output folder; the pictures go to DIR/pictures")->required();
  p->add_option("--scheme", opts->schemes,
                "scheme with a cpu backend, as name:key=value (repeatable; default: the paper schemes)");
  p->add_option("--mesh", opts->meshes, "mesh name or path (repeatable; default: Spot's control mesh, the frog stand-in, the icosphere)");
  p->add_option("--level", opts->level, "depth k or rate N for every scheme (default: per scheme and mesh, about 170 k triangles)");
  p->add_option("--width", opts->width, "picture width in pixels")->check(CLI::Range(16u, 4096u));
  p->add_option("--height", opts->height, "picture height in pixels")->check(CLI::Range(16u, 4096u));
  verbs["pictures"] = [opts] { return pictures_cmd(*opts); };
}

}  // namespace sdb::app
