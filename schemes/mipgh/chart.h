// Chart-morphic attributes (Section 4, Figure 18): one value per node of each D-facet, so that a
// node on a D-edge or at a corner carries one value per D-facet holding it (texture coordinates
// with a seam there, say). Addressed by hashing, as the paper has it: the list's base for the
// D-facet plus the node's offset in the D-facet's row-major array (N^2 in a quad, N(N+1)/2 in a
// triangle), no index array. Refined with the mesh, inside each D-facet alone: the 1-to-4 split
// interpolates linearly (midpoints of a micro-edge, the average of a micro-quad's four corners),
// which is OpenSubdiv's face-varying interpolation with FVAR_LINEAR_ALL, so every level holds the
// chart's bilinear (quad) or linear (triangle) interpolation of its corner values.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "schemes/mipgh/atlas.h"
#include "schemes/mipgh/lod.h"

namespace sdb::mipgh {

using ChartValue = std::array<float, 2>;

class ChartAttribute {
 public:
  // Levels 0..depth from corner_values[f][k], D-facet f's value at its corner k (atlas order).
  ChartAttribute(const DAtlas& atlas, int depth, const std::vector<std::array<ChartValue, 4>>& corner_values);
  // Each D-facet's own unit chart: u along side 0 and v along its last side, (0, 0) at corner 0
  // (a quad's corners (0, 0), (1, 0), (1, 1), (0, 1); a triangle's (0, 0), (1, 0), (0, 1)), so
  // that node (i, j) holds (j, i) / (N - 1).
  static ChartAttribute unit_charts(const DAtlas& atlas, int depth);

  int depth() const { return int(levels_.size()) - 1; }
  // The hash: D-facet f's base at level sigma plus the node's offset in its array.
  uint32_t address(int sigma, int f, RowColumn p) const {
    const int n = (1 << sigma) + 1;
    return base_[size_t(sigma)][size_t(f)] + uint32_t(facet_offset(sizes_[size_t(f)], n, p));
  }
  const ChartValue& at(int sigma, int f, RowColumn p) const { return levels_[size_t(sigma)][address(sigma, f, p)]; }
  const std::vector<ChartValue>& level(int sigma) const { return levels_[size_t(sigma)]; }

 private:
  void refine(int sigma);  // level sigma -> sigma + 1

  std::vector<uint8_t> sizes_;  // the D-facets' corners, 4 or 3
  std::vector<std::vector<uint32_t>> base_;  // per level, per D-facet
  std::vector<std::vector<ChartValue>> levels_;
};

}  // namespace sdb::mipgh
