// Which runs `subdivbench run` and `bench` perform: the user's selection, or the default set.
#pragma once

#include <string>
#include <vector>

#include "harness/bench/measure.h"
#include "harness/bench/paired.h"

namespace sdb {

struct Selection {
  std::vector<std::string> schemes;  // as spelled: "geometry-image:fit=129"
  std::vector<std::string> meshes, backends;
  std::vector<int> levels;
  bool all_meshes = false;  // every built-in and every real corpus mesh instead of the curated set
  bool all_corpus = false;  // with all_meshes: OpenSubdiv's regression shapes too
  long max_triangles = 1'000'000;  // default levels only: skip outputs larger than this
  bool headline = true;  // default set: also the schemes' headline runs (SchemeInfo::headline_runs)
  bool quick = false;    // the quick set (quick_meshes, quick_levels) instead of the default set
  // `run --shard I/N`: of the planned runs, sorted by name, those whose position p has
  // p % shard_count == shard_index; the same 1/N whatever the order of the command line.
  int shard_index = 0, shard_count = 1;
  bool operator==(const Selection&) const = default;
};

// What `run` is asked: the selection and the options that shape its rows. A journal records it,
// and a run is resumed only under the same one.
struct RunSelection {
  Selection selection;
  int reps = 5;
  long rays = 50000;
  uint64_t seed = 1;
  bool validate = true;
  bool operator==(const RunSelection&) const = default;
};

// The measuring options of a run's rows. A default set turns a scheme's late refusal of a mesh
// into an "unsupported" row; one scheme on one mesh keeps it an error (exit code 2).
MeasureOptions measure_options(const RunSelection& selection);

struct Plan {
  std::vector<RunSpec> runs;
  std::vector<std::string> notes;  // what was skipped and why, one line each
};

// Backends usable on this machine (vulkan only when a device answers).
std::vector<Backend> available_backends();

// Throws InputError when the user names an unknown scheme or backend, or names exactly one
// scheme and one mesh and the scheme refuses the mesh.
Plan make_plan(const Selection& selection, MeasureContext& context);

// `runs` with every run once, in the order of first mention: a selection that names a run twice
// (`--level 1 --level 1`, `bench --run X --run X`) measures it once, and its results and journal
// hold one row per run. Each repeat removed is noted in `notes` when given.
std::vector<RunSpec> distinct_runs(const std::vector<RunSpec>& runs, std::vector<std::string>* notes = nullptr);

// `run --shard`'s "I/N" as {I, N}; InputError unless 0 <= I < N.
std::pair<int, int> parse_shard(const std::string& text);

// The runs of shard `index` of `count`: the runs whose name's position among the sorted distinct
// names is index modulo count (every copy of a repeated run goes to the same shard).
std::vector<RunSpec> shard_runs(const std::vector<RunSpec>& runs, int index, int count);

// The quick set's meshes: a triangle mesh (a built-in) and one real corpus quad mesh (a built-in
// stand-in when the corpus is absent). A scheme runs on the one of its own rule: Loop schemes on
// the triangle mesh, Catmull-Clark schemes on the quad mesh.
struct QuickMesh {
  std::string name;
  SubdivisionRule rule;
};

// The summary cell's size band (kSummaryLow..kSummaryHigh, results.h). A scheme whose levels
// cannot reach it on a quick mesh (cpatch-1pass's N <= 9 on lavapipe: 12 k triangles on the quad
// sphere) runs on its rule's larger built-in instead (quick_fallback_mesh).
// A built-in of some ten thousand faces: the c-patch paper's Frog Party stand-in (11,628 random
// quads, 59% extraordinary; random quads past 1,300 are refused as too slow to make), or the
// icosphere subdivided to 20,480 triangles.
std::string quick_fallback_mesh(SubdivisionRule rule);
std::vector<QuickMesh> quick_meshes();

// Levels are chosen from the predicted output size (Scheme::estimated_triangles), not from a fixed
// list: every summary cell (the level nearest kSummaryTriangles) lands within a factor of two of it
// wherever the scheme's levels reach it (a depth step quadruples the output). Scanned: depths
// 0..kDeepestDepth, rates 2..kFinestRate, less what the scheme's unsupported() declines.
inline constexpr int kDeepestDepth = 12, kFinestRate = 257;

// The entry of `level_triangles` whose output is nearest `target` in ratio; end() when empty.
std::vector<std::pair<int, long>>::const_iterator nearest_level(const std::vector<std::pair<int, long>>& level_triangles,
                                                                long target);

// The quick set's two levels of a scheme on an accepted mesh: among the levels it takes, the one
// with the smallest output within kSummaryLow..kSummaryHigh (else the one nearest, in ratio,
// kSummaryTriangles), then of the rest the one nearest kQuickLow. Fewer when the scheme has fewer
// levels.
inline constexpr long kQuickLow = 100'000;
inline constexpr double kQuickMinTime = 0.02;  // seconds per timed repetition (default 0.05)
std::vector<int> quick_levels(const std::vector<std::pair<int, long>>& level_triangles);

// The meshes of the default set: the union of the meshes the schemes ask for
// (SchemeInfo::default_meshes: the papers' stand-ins, the real meshes the issues name, a few
// structural built-ins), in the manifest's order, so that `run` takes minutes, not an hour; with
// `all`, every built-in and every real corpus mesh (and OpenSubdiv's shapes with all_corpus).
std::vector<std::string> default_meshes(bool all, bool all_corpus);

}  // namespace sdb
