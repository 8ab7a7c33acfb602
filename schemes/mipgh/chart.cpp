#include "schemes/mipgh/chart.h"

#include <stdexcept>

namespace sdb::mipgh {

ChartAttribute::ChartAttribute(const DAtlas& atlas, int depth,
                               const std::vector<std::array<ChartValue, 4>>& corner_values)
    : sizes_(atlas.facet_size) {
  if (corner_values.size() != size_t(atlas.num_facets()))
    throw std::invalid_argument("chart attribute: one set of corner values per D-facet");
  for (int sigma = 0; sigma <= depth; ++sigma) {
    const uint32_t n = (1u << sigma) + 1;
    std::vector<uint32_t> base(sizes_.size());
    uint32_t next = 0;
    for (size_t f = 0; f < sizes_.size(); ++f) base[f] = next, next += sizes_[f] == 4 ? n * n : n * (n + 1) / 2;
    base_.push_back(std::move(base));
    levels_.emplace_back(next);
  }
  // Level 0 is the corners: a quad's 2 x 2 array (0, 0), (0, 1), (1, 0), (1, 1) holds its corners
  // 0, 1, 3, 2; a triangle's rows (0, 0), (0, 1) and (1, 0) its corners 0, 1, 2.
  for (int f = 0; f < atlas.num_facets(); ++f) {
    const auto& c = corner_values[size_t(f)];
    ChartValue* v = levels_[0].data() + base_[0][size_t(f)];
    if (sizes_[size_t(f)] == 4) v[0] = c[0], v[1] = c[1], v[2] = c[3], v[3] = c[2];
    else v[0] = c[0], v[1] = c[1], v[2] = c[2];
  }
  for (int sigma = 0; sigma < depth; ++sigma) refine(sigma);
}

ChartAttribute ChartAttribute::unit_charts(const DAtlas& atlas, int depth) {
  const std::array<ChartValue, 4> quad{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}}, triangle{{{0, 0}, {1, 0}, {0, 1}, {0, 0}}};
  std::vector<std::array<ChartValue, 4>> corners(size_t(atlas.num_facets()));
  for (int f = 0; f < atlas.num_facets(); ++f) corners[size_t(f)] = atlas.facet_size[f] == 4 ? quad : triangle;
  return ChartAttribute(atlas, depth, corners);
}

namespace {

ChartValue midpoint(const ChartValue& a, const ChartValue& b) { return {0.5f * (a[0] + b[0]), 0.5f * (a[1] + b[1])}; }

}  // namespace

void ChartAttribute::refine(int sigma) {
  const int n = (1 << sigma) + 1, m = 2 * n - 1;
  for (size_t f = 0; f < sizes_.size(); ++f) {
    const int size = sizes_[f];
    const ChartValue* src = levels_[size_t(sigma)].data() + base_[size_t(sigma)][f];
    ChartValue* dst = levels_[size_t(sigma) + 1].data() + base_[size_t(sigma) + 1][f];
    auto p = [&](int i, int j) -> const ChartValue& { return src[facet_offset(size, n, {i, j})]; };
    for (int r = 0; r < m; ++r)
      for (int c = 0; size == 4 ? c < m : r + c < m; ++c) {
        const int a = r >> 1, b = c >> 1;
        ChartValue& out = dst[facet_offset(size, m, {r, c})];
        if (!(r & 1) && !(c & 1)) out = p(a, b);
        else if (!(r & 1)) out = midpoint(p(a, b), p(a, b + 1));
        else if (!(c & 1)) out = midpoint(p(a, b), p(a + 1, b));
        else if (size == 3) out = midpoint(p(a, b + 1), p(a + 1, b));  // the micro-triangle's diagonal
        else  // a micro-quad's centre: the average of its corners
          for (int k = 0; k < 2; ++k) out[k] = 0.25f * ((p(a, b)[k] + p(a + 1, b + 1)[k]) + (p(a, b + 1)[k] + p(a + 1, b)[k]));
      }
  }
}

}  // namespace sdb::mipgh
