// A mesh's verdicts do not depend on where it lies or how large it is (issue 45): for every scheme,
// every mesh of the shared corpus and three copies of it, scaled by 1e-6 and by 1e6 and moved by
// ten times its diagonal, get the same verdict (ok, failed, unsupported or refused) at the
// scheme's lowest default level. The harness judges every mesh placed at unit size
// (harness/mesh/placement.h); before it did, a cube scaled by 1e10 failed with 180-degree normals.
// So the placed copy must also be the placed mesh, to the rounding of the copy's floats.
// The corpus is split into shards that ctest runs side by side; within a shard every scheme runs
// on a mesh in one MeasureContext, so that the schemes share its facts and reference surfaces.
// What a verdict does not read is left out (it cost more than 30 CPU-minutes with it): timing,
// Hausdorff distances, and the nearest-point deviation of schemes that declare no bound on it
// (MeasureOptions::unjudged_deviation: a LimitProjector of a million triangles per mesh and copy).
// What depends on the topology alone is made once for the mesh and its copies by whoever makes it:
// Far's limit stencil tables (schemes/peers/limit_stencils.h; 52-55 CPU-s per rule at the
// valence-360 poles, which eight runs per rule made again before).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "datasets/manifest.h"
#include "harness/bench/measure.h"
#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/mesh/mesh_io.h"
#include "harness/mesh/placement.h"

using namespace sdb;
namespace fs = std::filesystem;

namespace {

constexpr int kShards = 4;

// The copies of a mesh, as the harness would read them from files; the first is the mesh itself.
struct Copy {
  const char* what;
  double scale, offset_in_diagonals;
};
constexpr Copy kCopies[] = {{"as it is", 1, 0}, {"scaled by 1e-6", 1e-6, 0}, {"scaled by 1e6", 1e6, 0}, {"moved by ten diagonals", 1, 10}};

ControlMesh copy_of(const ControlMesh& m, const Copy& c) {
  ControlMesh out = m;
  const double shift = c.offset_in_diagonals * used_bounds(m).diagonal();
  for (auto& p : out.positions)
    for (float& x : p) x = static_cast<float>(double(x) * c.scale + shift);
  return out;
}

// A scheme as the sweep runs it: at its lowest default level, on cpu where it has it; a geometry
// image fits a 17 x 17 image (the default 65 costs seconds per mesh and copy).
struct SweepRun {
  std::string spelled;
  Backend backend;
  int level;
};

std::vector<SweepRun> sweep_runs() {
  std::vector<SweepRun> runs;
  for (const auto& s : all_schemes()) {
    const SchemeInfo& info = s->info();
    if (info.role == SchemeRole::Test) continue;
    const auto& b = info.backends;
    const Backend backend = std::find(b.begin(), b.end(), Backend::Cpu) != b.end() ? Backend::Cpu : b.front();
    const int level = *std::min_element(info.default_levels.begin(), info.default_levels.end());
    if (auto why = declined(*s, default_request(info, backend, level))) {
      std::printf("scale invariance: %s not run here: %s\n", info.name.c_str(), why->c_str());
      continue;
    }
    runs.push_back({info.name.rfind("geometry-image", 0) == 0 ? info.name + ":fit=17" : info.name, backend, level});
  }
  return runs;
}

// ok, failed or unsupported (the row's status), or refused; then the reason, which names files
// and figures the copies do not share.
std::string verdict(const RunSpec& spec, MeasureContext& context) {
  MeasureOptions o;
  o.time = false;
  o.rays = 200;
  o.hausdorff = false;  // reported, never judged: not part of a verdict
  o.unjudged_deviation = false;
  try {
    const RunRow row = measure_run(spec, o, context);
    return std::string(to_string(row.status)) + (row.status == RunStatus::Ok ? "" : " (" + row.message + ")");
  } catch (const InputError& e) {
    return std::string("refused (") + e.what() + ")";
  }
}

std::string kind_of(const std::string& verdict) { return verdict.substr(0, verdict.find(' ')); }

// How far the placed copy lies from the placed mesh, over the placed diagonal; or the refusal.
// What may differ is the rounding of the copy's floats, 2^-24 of its largest coordinate, and of the
// placed ones, 2^-24 of theirs: `allowed`.
struct Apart {
  double distance = 0, allowed = 0;
  bool mesh_refused = false, copy_refused = false;  // as degenerate geometry (placement.h)
};
Apart placed_apart(const ControlMesh& mesh, const ControlMesh& copy) {
  Apart a;
  ControlMesh placed, placed_copy;
  try {
    placed = placed_mesh(mesh);
  } catch (const InputError&) {
    a.mesh_refused = true;
  }
  try {
    placed_copy = placed_mesh(copy);
  } catch (const InputError&) {
    a.copy_refused = true;
  }
  if (a.mesh_refused || a.copy_refused) return a;
  // Placement scales by a power of two, so the two differ by the factor 1e6 leaves over one: each
  // is compared at its own diagonal.
  const double diagonal = used_bounds(placed).diagonal(), copy_diagonal = used_bounds(placed_copy).diagonal();
  double largest = 0, placed_largest = 0;
  for (size_t i = 0; i < copy.positions.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      largest = std::max(largest, std::abs(double(copy.positions[i][k])));
      placed_largest = std::max(placed_largest, std::abs(double(placed.positions[i][k])));
      a.distance = std::max(a.distance, std::abs(placed.positions[i][k] / diagonal - placed_copy.positions[i][k] / copy_diagonal));
    }
  a.allowed = 4 * std::ldexp(1.0, -24) * (largest / used_bounds(copy).diagonal() + 2 * placed_largest / diagonal);
  return a;
}

class ScaleInvariance : public ::testing::TestWithParam<int> {};

}  // namespace

TEST_P(ScaleInvariance, EveryCorpusMeshGetsOneVerdictAtAnyScaleOrPlace) {
  if (!corpus_dir()) GTEST_SKIP() << "shared corpus not found beside the checkout";
  const int shard = GetParam();
  const std::vector<SweepRun> runs = sweep_runs();
  const fs::path dir = fs::temp_directory_path() / ("scale_invariance_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::map<std::string, std::map<std::string, int>> counts;  // scheme -> the originals' verdicts, counted
  int meshes = 0, index = 0, refused_geometry = 0;
  for (const auto& entry : list_meshes()) {
    if (entry.kind != "corpus" || index++ % kShards != shard) continue;
    ++meshes;
    const ControlMesh mesh = load_mesh(entry.name);
    std::vector<std::string> original(runs.size());
    for (const Copy& c : kCopies) {
      const bool first = &c == kCopies;
      const std::string file = (dir / (std::to_string(&c - kCopies) + ".obj")).string();
      if (!first) {
        write_obj(copy_of(mesh, c), file);
        const Apart a = placed_apart(mesh, load_mesh(file));
        EXPECT_EQ(a.copy_refused, a.mesh_refused) << entry.name << " " << c.what << ": refused as degenerate geometry";
        EXPECT_LE(a.distance, a.allowed) << entry.name << " " << c.what << ": the placed copy is not the placed mesh";
        refused_geometry += a.copy_refused;
      }
      MeasureContext context{MachineInfo{}};
      for (size_t r = 0; r < runs.size(); ++r) {
        const std::string v = verdict({runs[r].spelled, first ? entry.name : file, runs[r].backend, runs[r].level}, context);
        if (first) {
          original[r] = v;
          ++counts[runs[r].spelled][kind_of(v)];
        } else {
          EXPECT_EQ(kind_of(v), kind_of(original[r])) << runs[r].spelled << " on " << entry.name << " " << c.what << " at level "
                                                      << runs[r].level << ": " << v << "; as it is: " << original[r];
        }
      }
    }
  }
  fs::remove_all(dir);
  for (const auto& [scheme, kinds] : counts) {
    std::string line;
    for (const auto& [kind, n] : kinds) line += " " + kind + " " + std::to_string(n);
    std::printf("scale invariance, shard %d/%d: %s on %d corpus meshes and 3 copies of each:%s\n", shard, kShards, scheme.c_str(),
                meshes, line.c_str());
  }
  std::printf("scale invariance, shard %d/%d: %d corpus meshes x %zu scheme runs x %zu copies judged (%d copies refused as "
              "degenerate geometry)\n",
              shard, kShards, meshes, runs.size(), std::size(kCopies) - 1, refused_geometry);
  EXPECT_GE(meshes, 100 / kShards);
}

INSTANTIATE_TEST_SUITE_P(CorpusShards, ScaleInvariance, ::testing::Range(0, kShards));
