// The Vulkan evaluation's dispatches (vulkan.cpp), in order: level 0's gather; per level its face
// points (Catmull-Clark), edge points and vertex points; the limit. The vertex points and the
// limit are split by kind (device_tables.h), a dispatch per frequent kind with its pipeline
// specialized on it, because lavapipe runs every side of a branch masked, so one generic kernel
// pays for every rule's formula on every entry.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "schemes/fragments/device_tables.h"
#include "schemes/fragments/surface.h"

namespace sdb::fragments {

// Entries of a pass per invocation, at most (a power of two).
constexpr uint32_t kMaxChunk = 64;

// fragments.glsl's kPart values. Patch: the normals of shapes with a patch polynomial (tables.h),
// in the limit's time, one invocation per fragment and chunk of rows (patch_normals.comp).
enum class Part : uint32_t { Gather = 0, Faces = 1, Edges = 2, Limit = 3, Vertices = 4, Patch = 5 };

struct PassSpec {
  Part part;
  uint32_t level = 0;             // Faces, Edges, Vertices: the level the pass makes
  // Specialization constant 3: Vertices, its rule case; Limit, its kind; Patch, 1 for triangles.
  uint32_t key = 0;
  uint32_t kind_pairs = 0;        // Vertices, Limit: the tables' word of its (list, count) pair for shape 0
  uint32_t chunk = kMaxChunk;     // entries per invocation
  // Per shape, per chunk of its entries: the sum of their costs (loop iterations, bounded from
  // above); a work group per chunk and batch (vulkan.cpp, append_work_items).
  std::vector<std::vector<uint64_t>> chunk_costs;
};

// The passes of `s`, their kinds' entry lists appended to `tables`. Each pass takes the largest
// chunk that keeps every invocation within kLoopBudget loop iterations; where even one entry does
// not fit and the device is `loop_limited` (llvmpipe), throws Unsupported naming `device`.
std::vector<PassSpec> plan_passes(const FragmentSurface& s, DeviceTables& tables, bool project, bool loop_limited,
                                  const std::string& device);

// A work group of a pass's dispatch: a chunk of its entries for one batch of the wave, and what
// it costs (the chunk's entries' costs times the batch's subgroups).
struct WorkItem {
  uint32_t chunk = 0, batch = 0;
  uint64_t cost = 0;
};

// `items` in the order to dispatch them. lavapipe hands each of its T threads one contiguous 1/T of
// a dispatch's work groups (Mesa's lp_cs_tpool), so batches in shape order put the costly vertex
// patches on one thread. Batches ranked by their items' cost, batch r goes where the bits of r
// reversed say, which spreads every rank over every contiguous stretch, whatever T; a batch's
// items stay together and in order, so that a thread keeps one batch's scratch in its cache (the
// frog stand-in's level 4 took 30% longer with the items of a batch apart).
std::vector<WorkItem> interleave_by_cost(const std::vector<WorkItem>& items);

// The timestamp label a pass is timed under ("gather", "level 2", "limit").
std::string pass_label(const PassSpec& pass);

}  // namespace sdb::fragments
