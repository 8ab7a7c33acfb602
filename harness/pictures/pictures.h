// Pictures of the schemes' surfaces for the report: each paper scheme's tessellation (from its
// cpu backend) on a few meshes, rendered offscreen by harness/gpu's renderer, once shaded and once
// coloured by its distance from the OpenSubdiv limit at the same surface point, with a colour bar.
//
//   DIR/pictures/<scheme>_<mesh>_{shaded,deviation}.png, colour-bar.png, pictures.json
//
// pictures.json (schema 1; "reason" only when unavailable, "device" and "colour_bar" only when
// available, "deviation_range" only on deviation pictures, "error" and no "file" on a picture that
// failed):
//   {"schema": 1, "available": true, "device": "...", "colour_bar": "colour-bar.png",
//    "pictures": [{"scheme", "mesh", "level", "backend", "triangles", "kind", "file",
//                  "deviation_range": [0, max] /* of the bounding-box diagonal */, "error"}]}
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/scheme.h"

namespace sdb::pictures {

struct PictureRequest {
  std::vector<std::string> schemes;  // as spelled on the command line; empty: default_schemes()
  std::vector<std::string> meshes;   // empty: default_meshes()
  std::optional<int> level;          // for every scheme; empty: per scheme and mesh, picture_level()
  uint32_t width = 640, height = 480;
};

struct PictureEntry {
  std::string scheme, mesh;
  int level = 0;
  std::string backend = "cpu";
  long triangles = 0;
  std::string kind;  // "shaded" or "deviation"
  std::string file;  // relative to DIR/pictures; empty when the picture failed
  std::optional<std::pair<double, double>> deviation_range;
  std::string error;  // why there is no picture
};

struct PictureManifest {
  bool available = false;
  std::string reason;  // when not available
  std::string device;
  std::string colour_bar;
  std::vector<PictureEntry> pictures;
  // Scheme and mesh pairs left out because the scheme does not take the mesh (not in the JSON).
  std::vector<std::string> notes;
};

// The paper schemes of the registry (methods, not peers) that have a cpu backend, one per paper
// and subdivision rule: the others are variants that organise the GPU's work differently and
// draw the same surface (geometry-image-permask beside geometry-image).
std::vector<std::string> default_schemes();

// Spot's control mesh when the corpus is present (a real mesh; else the pole5 built-in, closed,
// genus 0, with extraordinary vertices), the frog stand-in (the c-patch paper's model) and the
// icosphere (for the Loop scheme).
std::vector<std::string> default_meshes();

// The level (depth or rate) whose estimated output is nearest, by ratio, to about 170 k triangles
// (between 100 k and 300 k where the scheme's levels allow): a picture rendered in seconds on a
// CPU device, dense enough that no facet shows.
int picture_level(const Scheme& scheme, const ControlMesh& accepted, const Parameters& parameters);

// Called after each picture is written (or has failed), for progress lines.
using PictureCallback = std::function<void(const PictureEntry&)>;

// Writes the pictures and DIR/pictures/pictures.json, the manifest last (written whole, then
// renamed: a manifest present is complete). Without a Vulkan device: the manifest with available
// false and the reason. A picture that fails is an entry with its error; the others are still
// drawn. Throws InputError (nothing written) for an unknown scheme or mesh, a scheme without a
// cpu backend, or a DIR that cannot be made.
PictureManifest write_pictures(const PictureRequest& request, const std::string& out_dir,
                               const PictureCallback& on_picture = {});

}  // namespace sdb::pictures
