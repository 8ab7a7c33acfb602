#include "schemes/geometry-image/subdivision.h"

#include <stdexcept>

namespace sdb::gim {

Subdivider::Subdivider(int base_size, int levels, PassPlan plan)
    : base_size_(base_size), levels_(levels), plan_(plan), gather_(padding_gather_table(CutSymmetry(base_size))) {
  if (levels < 0) throw std::invalid_argument("negative subdivision level");
  for (int k = 0; k <= levels; ++k) images_.emplace_back(size(k) + 2);
  if (plan == PassPlan::PerMask && levels > 0) split_ = PaddedImage(2 * images_[levels - 1].side - 1);
  cut_stencils_ = cut_vertex_stencils(size(levels));
}

void Subdivider::run(const Point3* control, Point3* positions, Point3* normals, const RowExecutor& rows) {
  auto pad = [&](RowRange r) { pad_pass(gather_, control, images_[0], r); };
  rows.for_rows(images_[0].side, pad);
  for (int k = 0; k < levels_; ++k) {
    const PaddedImage& src = images_[k];
    PaddedImage& dst = images_[k + 1];
    if (plan_ == PassPlan::Fused) {
      auto fused = [&](RowRange r) { split_average_pass(src, dst, r); };
      rows.for_rows(dst.side, fused);
    } else {
      // The scratch keeps its capacity; only its side (and so its plane offsets) changes.
      split_.side = 2 * src.side - 1;
      auto split = [&](RowRange r) { split_pass(src, split_, r); };
      rows.for_rows(split_.side, split);
      auto average = [&](RowRange r) { average_pass(split_, dst, r); };
      rows.for_rows(dst.side, average);
    }
  }
  const PaddedImage& last = images_[levels_];
  const int n = last.side - 2;
  if (plan_ == PassPlan::Fused) {
    auto frame = [&](RowRange r) { limit_normal_pass(last, positions, normals, r); };
    rows.for_rows(n, frame);
  } else {
    auto limit = [&](RowRange r) { limit_pass(last, positions, r); };
    rows.for_rows(n, limit);
    auto normal = [&](RowRange r) { normal_pass(last, normals, r); };
    rows.for_rows(n, normal);
  }
  cut_vertex_normal_pass(last, cut_stencils_, normals);
}

}  // namespace sdb::gim
