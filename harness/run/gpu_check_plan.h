// What `subdivbench gpu-check` measures, from the registry alone: every scheme with a GPU backend
// (the paper methods' Vulkan paths, the GPU peers) on the first of its meshes that gives outputs of
// the wanted size, at two sizes, each beside a CPU row of the same output (its own cpu-mt row, else
// its peer's on the peer's backend). A scheme added to the registry joins without an edit here.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "harness/bench/measure.h"

namespace sdb {

// Output sizes in triangles: the first size is the level nearest `target` among those within
// [min, max]; the second the level nearest four times the first's output, up to `max`, else a
// quarter of it (a second point of the cost curve).
struct OutputBounds {
  long min = 0, target = 0, max = 0;
};
// On a GPU: 10-60 M triangles (the 10-100 M, kept to 60 M so that two sizes of every
// scheme fit the ten minutes with their CPU rows).
inline constexpr OutputBounds kGpuCheckBounds{10'000'000, 15'000'000, 60'000'000};
// --quick (any device, lavapipe in the tests): small outputs.
inline constexpr OutputBounds kGpuCheckQuickBounds{10'000, 50'000, 300'000};

// One scheme at one size: its GPU rows and the CPU row beside them, benchmarked together in paired
// rounds by one `bench` (so that each GPU row's ratio to its CPU row is paired by round).
struct CheckGroup {
  int size = 1;        // 1 or 2
  std::string scheme;  // as spelled (its name)
  std::string mesh;
  int level = 0;
  long triangles = 0;         // the GPU row's output, estimated
  std::vector<RunSpec> runs;  // GPU rows first, then the CPU row
  std::string name() const;   // "size 1: cpatch-2pass"
  std::string slug() const;   // "1-cpatch-2pass", a folder name
};

struct CheckPlan {
  std::vector<CheckGroup> groups;  // every scheme at size 1, then at size 2; methods before peers in each
  std::vector<std::string> notes;  // schemes left out and why
};

// `gpu_backends`: the GPU backends usable here (vulkan, opengl); `quick`: small outputs, each
// scheme's default meshes tried first (check_mesh_candidates).
CheckPlan plan_gpu_check(const OutputBounds& bounds, bool quick, const std::vector<Backend>& gpu_backends,
                         MeasureContext& context);

// The two levels from a scheme's supported levels and their outputs (ascending by level): the
// first nearest `target` among those within [min, max] (the largest output up to max where none
// is within), the second as OutputBounds says; one or none where there are fewer.
std::vector<int> check_levels(const std::vector<std::pair<int, long>>& level_triangles, const OutputBounds& bounds);

// The meshes a scheme's large outputs are tried on, in order (SchemeInfo::large_meshes, else its
// headline runs' meshes then its default meshes); with `quick`, its default meshes first.
std::vector<std::string> check_mesh_candidates(const SchemeInfo& info, bool quick);

}  // namespace sdb
