// The D-facet visits' tile (processor.cpp): a facet's nodes of one level in three float planes,
// and the stencils that run over its whole square in SIMD lanes. Plain loops over floats; the
// processor gathers the tile and assembles the targets.
#pragma once

#include <cstdint>
#include <vector>

#include "schemes/mipgh/shader.h"

namespace sdb::mipgh::tile {

// A D-facet's nodes of one level, gathered once through its index array into three planes (the
// work-group tile a GPU would stage in shared memory). A plane is the n x n square, a triangle in
// its lower-left half (row i holds n - i nodes), with n + 1 floats of padding on either side: the
// stencils then run over the whole square as one long SIMD loop with fixed neighbour offsets
// (+-1 along a row, +-n across), and the values at squares no target uses are dropped.
struct Tile {
  std::vector<float> storage[3];
  int n = 0;
  float* plane(int k) { return storage[k].data() + n + 1; }
  const float* plane(int k) const { return storage[k].data() + n + 1; }
  void load(const uint32_t* idx, int size, const V3* src, bool quad) {
    if (n != size)
      for (auto& s : storage) s.assign(size_t(size) * size + 2 * (size + 1), 0.0f);
    n = size;
    float *x = plane(0), *y = plane(1), *z = plane(2);
    // float by float: a V3 copied whole goes through the stack (store forwarding on every node)
    const float* base = &src[0].x;
    if (quad) {
      for (int i = 0; i < n * n; ++i) {
        const float* p = base + size_t(idx[i]) * 3;
        x[i] = p[0], y[i] = p[1], z[i] = p[2];
      }
      return;
    }
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        const float* p = base + size_t(*idx++) * 3;
        x[i * n + j] = p[0], y[i * n + j] = p[1], z[i * n + j] = p[2];
      }
  }
};

// The stencils' results over a tile's square: four classes of target per source square L = (a, b)
// (the target at (2a + r, 2b + c) for class 2r + c), or the limit position and two tangents.
struct Planes {
  std::vector<float> v[4][3], normal[3];
  size_t size = 0;
  void fit(size_t wanted) {
    if (wanted == size) return;
    size = wanted;
    for (auto& c : v)
      for (auto& p : c) p.resize(size);
    for (auto& p : normal) p.resize(size);
  }
};

// Figure 20's stencils at every square of one coordinate's plane P (n x n, padded): vertex points
// (class 0), horizontal edge points (1), vertical ones (2), facet points (3).
void quad_classes(const float* P, int n, float* vv, float* eh, float* ev, float* fv);
// Loop's, in a triangle's square: vertex points (0), edge points of (a, b)-(a, b+1) (1),
// (a, b)-(a+1, b) (2) and the diagonal (a, b+1)-(a+1, b) (3).
void triangle_classes(const float* P, int n, float* vv, float* eh, float* ev, float* ed);
// The limit position and the two tangents at every square (catmark_limit_regular and
// loop_limit_regular's masks).
void quad_limit(const float* P, int n, float* pos, float* t1, float* t2);
void triangle_limit(const float* P, int n, float* pos, float* t1, float* t2);
// Unit T1 x T2 at every square.
void unit_normals(const float* ax, const float* ay, const float* az, const float* bx, const float* by, const float* bz,
                  float* nx, float* ny, float* nz, int count);

}  // namespace sdb::mipgh::tile
