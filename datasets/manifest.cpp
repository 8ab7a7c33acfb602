#include "datasets/manifest.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <regex>

#include "datasets/generators.h"
#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/mesh/mesh_io.h"

namespace fs = std::filesystem;

namespace sdb {
namespace {

struct Builtin {
  const char* name;
  const char* description;
  std::function<ControlMesh()> make;
};

// Stand-ins for the c-patch paper's models (TABLES.md): same quad count and extraordinary share.
const std::vector<Builtin>& builtins() {
  static const std::vector<Builtin> list = {
      {"cube", "cube, 6 quads, eight valence-3 corners", [] { return gen::cube(); }},
      {"torus", "torus grid 16x32 quads, all regular", [] { return gen::torus(16, 32); }},
      {"torus-8x8", "torus grid 8x8 quads, all regular", [] { return gen::torus(8, 8); }},
      {"quadsphere", "cube-sphere, 6 x 4^2 quads", [] { return gen::quad_sphere(4); }},
      {"pole3", "closed quad mesh with two valence-3 poles", [] { return gen::pole(3); }},
      {"pole4", "closed quad mesh with two valence-4 poles", [] { return gen::pole(4); }},
      {"pole5", "closed quad mesh with two valence-5 poles", [] { return gen::pole(5); }},
      {"pole6", "closed quad mesh with two valence-6 poles", [] { return gen::pole(6); }},
      {"pole7", "closed quad mesh with two valence-7 poles", [] { return gen::pole(7); }},
      {"pole8", "closed quad mesh with two valence-8 poles", [] { return gen::pole(8); }},
      {"icosphere", "icosphere, 320 triangles", [] { return gen::icosphere(2); }},
      {"tetrahedron", "tetrahedron, 4 triangles", [] { return gen::tetrahedron(); }},
      {"creased-cube", "cube, every edge crease sharpness 2", [] { return gen::creased_cube(2.0f); }},
      {"open-patch", "8x8 quad patch with boundary", [] { return gen::open_patch(8, 8); }},
      {"sword-standin", "random quads: 138 quads, 38% extraordinary (the paper's Sword)",
       [] { return gen::random_quads(138, 0.38, 1); }},
      {"head-standin", "random quads: 600 quads, 100% extraordinary (the paper's Head)",
       [] { return gen::random_quads(600, 1.00, 1); }},
      {"frog-standin", "random quads: 1292 quads, 59% extraordinary (the paper's Frog)",
       [] { return gen::random_quads(1292, 0.59, 1); }},
      {"frog-party", "nine frog stand-ins (the paper's Frog Party)",
       [] { return gen::party(gen::random_quads(1292, 0.59, 1), 9); }},
      {"frog-party-triangles", "the frog party's quads split in two: 23,256 triangles of valence 3 to 11",
       [] { return gen::split_quads(gen::party(gen::random_quads(1292, 0.59, 1), 9)); }},
  };
  return list;
}

// The generators' own meshes, then those the scheme folders provide (SDB_REGISTER_MESHES).
const std::vector<NamedMesh>& named_meshes() {
  static const std::vector<NamedMesh> all = [] {
    std::vector<NamedMesh> list;
    for (const Builtin& b : builtins()) list.push_back({b.name, b.description, b.make});
    for (const MeshProvider& p : mesh_providers()) list.insert(list.end(), p.builtins.begin(), p.builtins.end());
    return list;
  }();
  return all;
}

// A generated mesh past this many faces is a typo, not a benchmark: refused before allocating.
constexpr double kMaxGeneratedFaces = 4e6;

struct NameParser {
  const std::string& name;
  std::smatch m;

  // libstdc++'s regex recurses once per character: a 60,000-character name overflowed the stack.
  // No generator name is longer than this (its numbers are at most 10 digits each).
  static constexpr size_t kLongestName = 64;
  bool match(const char* pattern) { return name.size() <= kLongestName && std::regex_match(name, m, std::regex(pattern)); }
  long number(int k) const {
    long v = 0;
    const std::string s = m[k].str();
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || end != s.data() + s.size() || v > INT32_MAX)
      throw InputError(name, "number " + s + " out of range");
    return v;
  }
  void check_faces(double faces) const {
    if (faces > kMaxGeneratedFaces)
      throw InputError(name, "would have " + std::to_string(static_cast<long long>(std::min(faces, 1e18))) +
                                 " faces, more than the " + std::to_string(long(kMaxGeneratedFaces)) +
                                 " a generated mesh may have");
  }
};

std::optional<ControlMesh> parametrised_unchecked(NameParser& p) {
  auto n = [&](int k) { return p.number(k); };
  if (p.match(R"(torus-(\d+)x(\d+))")) return p.check_faces(double(n(1)) * n(2)), gen::torus(n(1), n(2));
  if (p.match(R"(quadsphere-(\d+))")) return p.check_faces(6.0 * n(1) * n(1)), gen::quad_sphere(n(1));
  if (p.match(R"(icosphere-(\d+))")) return p.check_faces(20 * std::pow(4.0, n(1))), gen::icosphere(n(1));
  if (p.match(R"(pole(\d+))")) return p.check_faces(10.0 * n(1)), gen::pole(n(1));
  if (p.match(R"(open-patch-(\d+)x(\d+))")) {
    if (n(1) < 1 || n(2) < 1) throw InputError(p.name, "needs at least 1 x 1 quads");
    return p.check_faces(double(n(1)) * n(2)), gen::open_patch(n(1), n(2));
  }
  if (p.match(R"(random-(\d+)-(\d+)(?:-(\d+))?)")) {
    if (n(2) > 100) throw InputError(p.name, "extraordinary share " + std::to_string(n(2)) + "% is over 100%");
    return p.check_faces(double(n(1))), gen::random_quads(n(1), n(2) / 100.0, p.m[3].matched ? n(3) : 1);
  }
  for (const MeshProvider& prov : mesh_providers())
    if (prov.parse)
      if (auto mesh = prov.parse(p.name)) return mesh;
  return std::nullopt;
}

// Generator names with their parameters; a generator's own refusal is given the full name.
std::optional<ControlMesh> parametrised(const std::string& name) {
  NameParser p{name, {}};
  try {
    return parametrised_unchecked(p);
  } catch (const InputError& e) {
    const std::string what = e.what();
    if (what.rfind(name + ":", 0) == 0) throw;
    const size_t colon = what.find(": ");
    throw InputError(name, colon == std::string::npos ? what : what.substr(colon + 2));
  }
}

bool is_mesh_file(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".obj" || ext == ".off" || ext == ".ply";
}

}  // namespace

std::optional<std::string> corpus_dir() {
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv("SUBDIVBENCH_DATASETS"); env && *env) candidates.emplace_back(env);
  candidates.emplace_back(fs::path(SDB_SOURCE_DIR) / ".." / "shared" / "datasets");
  candidates.emplace_back(fs::current_path() / ".." / "shared" / "datasets");
  for (const auto& c : candidates) {
    std::error_code ec;
    if (fs::is_directory(c, ec)) return fs::weakly_canonical(c).string();
  }
  return std::nullopt;
}

std::vector<MeshEntry> list_meshes() {
  std::vector<MeshEntry> out;
  for (const auto& b : named_meshes()) out.push_back({b.name, "builtin", b.description});
  if (auto dir = corpus_dir()) {
    std::vector<MeshEntry> corpus;
    // error_code throughout: an entry whose status cannot be had (a symbolic-link loop, a file
    // removed meanwhile, a folder it may not read) is not a mesh, and not an internal error.
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(*dir, fs::directory_options::skip_permission_denied, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
      const fs::directory_entry& e = *it;
      std::error_code status;
      if (!e.is_regular_file(status) || !is_mesh_file(e.path())) continue;
      fs::path rel = fs::relative(e.path(), *dir, status);
      if (status) continue;
      corpus.push_back({rel.replace_extension().string(), "corpus", e.path().string()});
    }
    std::sort(corpus.begin(), corpus.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
    out.insert(out.end(), corpus.begin(), corpus.end());
  }
  return out;
}

namespace {

std::optional<fs::path> corpus_file(const std::string& name) {
  const auto dir = corpus_dir();
  if (!dir) return std::nullopt;
  std::error_code ec;
  const fs::path base = fs::path(*dir) / name;
  if (fs::is_regular_file(base, ec)) return base;
  for (const char* ext : {".obj", ".off", ".ply"}) {
    fs::path p = base;
    p += ext;
    if (fs::is_regular_file(p, ec)) return p;
  }
  return std::nullopt;
}

}  // namespace

bool corpus_has(const std::string& name) { return corpus_file(name).has_value(); }

std::optional<ControlMesh> generated_mesh(const std::string& name) {
  for (const auto& b : named_meshes())
    if (name == b.name) {
      ControlMesh m = b.make();
      m.name = b.name;
      return m;
    }
  return parametrised(name);
}

ControlMesh load_mesh(const std::string& name) {
  if (auto m = generated_mesh(name)) return *m;
  std::error_code ec;
  if (fs::is_regular_file(name, ec)) return read_mesh(name);
  if (auto file = corpus_file(name)) {
    ControlMesh m = read_mesh(file->string());
    if (file->has_extension() && fs::path(name).extension() != file->extension()) m.name = name;
    return m;
  }
  if (is_mesh_file(name)) return read_mesh(name);  // gives the "no such file" message
  throw InputError(name, "no such mesh: not a built-in name, a corpus name or a file (see `subdivbench list meshes`)");
}

}  // namespace sdb
