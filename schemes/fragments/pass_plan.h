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

// fragments.glsl's kPart values.
enum class Part : uint32_t { Gather = 0, Faces = 1, Edges = 2, Limit = 3, Vertices = 4 };

struct PassSpec {
  Part part;
  uint32_t level = 0;             // Faces, Edges, Vertices: the level the pass makes
  uint32_t key = 0;               // Vertices: its rule case; Limit: its kind (specialization constant 3)
  uint32_t kind_pairs = 0;        // Vertices, Limit: the tables' word of its (list, count) pair for shape 0
  uint32_t chunk = kMaxChunk;     // entries per invocation
  std::vector<uint32_t> entries;  // per shape
};

// The passes of `s`, their kinds' entry lists appended to `tables`. Each pass takes the largest
// chunk that keeps every invocation within kLoopBudget loop iterations; where even one entry does
// not fit and the device is `loop_limited` (llvmpipe), throws Unsupported naming `device`.
std::vector<PassSpec> plan_passes(const FragmentSurface& s, DeviceTables& tables, bool project, bool loop_limited,
                                  const std::string& device);

// The timestamp label a pass is timed under ("gather", "level 2", "limit").
std::string pass_label(const PassSpec& pass);

}  // namespace sdb::fragments
