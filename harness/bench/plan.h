// Which runs `subdivbench run` and `bench` perform: the user's selection, or the default set.
#pragma once

#include <string>
#include <vector>

#include "measure.h"

namespace sdb {

struct Selection {
  std::vector<std::string> schemes, meshes, backends;
  std::vector<int> levels;
  bool all_corpus = false;  // the default set takes the real corpus meshes; this adds OpenSubdiv's shapes
  long max_triangles = 8'000'000;  // default set only: skip outputs larger than this
};

struct Plan {
  std::vector<RunSpec> runs;
  std::vector<std::string> notes;  // what was skipped and why, one line each
};

// Backends usable on this machine (vulkan only when a device answers).
std::vector<Backend> available_backends();

// Throws InputError when the user names an unknown scheme or backend, or names exactly one
// scheme and one mesh and the scheme refuses the mesh.
Plan make_plan(const Selection& selection, MeasureContext& context);

// The meshes of the default set: every built-in, then the corpus's real meshes.
std::vector<std::string> default_meshes(bool all_corpus);

}  // namespace sdb
