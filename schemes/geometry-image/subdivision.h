// Subdivider: the per-frame work of Section 5, g0 -> g1 -> ... -> gk -> (p^k, n^k), as a fixed
// sequence of MaskPasses over buffers sized once. Two plans:
//   PerMask: one pass per mask, as the paper's Radeon implementation: pad; L, A per level; E; T.
//   Fused:   the fusions the paper anticipates for GPUs with more texture reads: L+A in one pass
//            per level, and E with the normals in one pass.
// Both finish with the cut-vertex normal pass, keep the cut symmetry bit for bit, and differ from
// each other by the rounding of L+A only (the fused E+T pass is bit-identical to E then T).
#pragma once

#include <cstddef>
#include <type_traits>
#include <utility>
#include <vector>

#include "schemes/geometry-image/masks.h"

namespace sdb::gim {

enum class PassPlan { PerMask, Fused };

// A non-owning reference to a callable taking a RowRange (no allocation, unlike std::function).
class RowBody {
 public:
  template <class F>
  RowBody(F& f) : object_(&f), call_([](void* o, RowRange r) { (*static_cast<F*>(o))(r); }) {}
  void operator()(RowRange r) const { call_(object_, r); }

 private:
  void* object_;
  void (*call_)(void*, RowRange);
};

// Distributes the rows of one pass: all at once (cpu) or in blocks across threads (cpu-mt).
// Every row is computed by the same code either way, so results are identical.
class RowExecutor {
 public:
  virtual ~RowExecutor() = default;
  virtual void for_rows(int rows, RowBody body) const = 0;
};

class SerialRows final : public RowExecutor {
 public:
  void for_rows(int rows, RowBody body) const override { body({0, rows}); }
};

// Sizes of level k of an image n0 x n0: n_k = (n0 - 1) 2^k + 1 samples a side, padded side n_k + 2.
inline int level_size(int n0, int k) { return (n0 - 1) * (1 << k) + 1; }

class Subdivider {
 public:
  Subdivider(int base_size, int levels, PassPlan plan);

  int levels() const { return levels_; }
  int size(int k) const { return level_size(base_size_, k); }
  PassPlan plan() const { return plan_; }
  // Control positions of g0 (closed-mesh vertex order) -> p^k, n^k, (size(levels))^2 each,
  // row-major. Allocates nothing.
  void run(const Point3* control, Point3* positions, Point3* normals, const RowExecutor& rows);
  // Padded g^k of the last run (k = 0..levels), for tests and the level-of-detail blend.
  const PaddedImage& level(int k) const { return images_[k]; }

 private:
  int base_size_, levels_;
  PassPlan plan_;
  std::vector<int> gather_;
  std::vector<PaddedImage> images_;  // g^0 .. g^k, padded
  PaddedImage split_;                // L[g^k] for the per-mask plan, sized for the largest level
  std::array<CutVertexStencil, 4> cut_stencils_;  // of the last level
};

}  // namespace sdb::gim
