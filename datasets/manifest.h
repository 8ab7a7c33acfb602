// The named meshes: built-in generators and, when present, the shared corpus
// (../shared/datasets beside the checkout, or $SUBDIVBENCH_DATASETS).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harness/core/control_mesh.h"

namespace sdb {

struct MeshEntry {
  std::string name;         // what `--mesh` takes
  std::string kind;         // "builtin" or "corpus"
  std::string description;  // generator and parameters, or the file path
};

// Built-in names first (the generators' fixed list, then the meshes scheme folders register with
// SDB_REGISTER_MESHES, e.g. gim-sphere-31), then every .obj/.off/.ply of the corpus by relative
// path without extension, e.g. "crane/spot_control".
std::vector<MeshEntry> list_meshes();

// A manifest name, a parametrised generator name (torus-MxN, quadsphere-K, icosphere-L,
// pole<N>, open-patch-MxN, random-Q-P[-S], and those of registered providers: gim-sphere-N), a
// corpus name, or a path to a file.
ControlMesh load_mesh(const std::string& name);

// The names load_mesh resolves without a file: a built-in name or a parametrised generator name
// (those of registered providers included). The mesh; nullopt for a name of another form;
// InputError, naming `name`, for a generator name it refuses (too small, past 4 M faces, ...).
std::optional<ControlMesh> generated_mesh(const std::string& name);

std::optional<std::string> corpus_dir();

// Whether the corpus is present and holds NAME (as load_mesh resolves it), without reading it.
bool corpus_has(const std::string& name);

}  // namespace sdb
