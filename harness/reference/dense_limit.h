// A dense tessellation of the reference limit surface, for two-sided Hausdorff distances: every
// base face at one rate (about two million triangles in all), each point evaluated once by the
// LimitEvaluator on a shared layout, so the surface is watertight; with its Embree scene.
// Catmull-Clark and Loop alike. Part of the yardstick, never a contestant.
#pragma once

#include <memory>

#include "harness/core/tessellation.h"
#include "harness/reference/embree_scene.h"
#include "harness/reference/limit_evaluator.h"

namespace sdb {

struct DenseLimit {
  Tessellation surface;
  std::unique_ptr<EmbreeTriangleScene> scene;
};

// Segments per base-face edge for a mesh of `faces` faces: dense enough for 1e-4 of the diagonal
// on the meshes here, at most 32.
int dense_limit_segments(int faces);

// The limit surface of `limit`'s mesh at `segments` per base-face edge on a shared layout (border
// points evaluated once: closed for a closed mesh), with positions, unit normals and SurfaceCoords.
Tessellation limit_tessellation(const LimitEvaluator& limit, int segments);

// limit_tessellation at dense_limit_segments, and its Embree scene.
DenseLimit dense_limit(const LimitEvaluator& limit);

}  // namespace sdb
