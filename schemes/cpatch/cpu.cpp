#include "schemes/cpatch/cpu.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "harness/core/errors.h"

namespace sdb::cpatch {

CpatchCpuEvaluation::CpatchCpuEvaluation(const ControlMesh& quads, int rate, bool multithreaded, int threads)
    : topology_(build_topology(quads)),
      converter_(topology_),
      grid_(rate),
      multithreaded_(multithreaded),
      scratch_(rate * rate),
      thread_scratch_([rate] { return PatchScratch(rate * rate); }) {
  // Tessellation indexes vertices with uint32_t.
  if (static_cast<uint64_t>(topology_.num_quads) * grid_.samples() > std::numeric_limits<uint32_t>::max())
    throw Unsupported(quads.source + ": cpatch-2pass at N = " + std::to_string(rate) + " on " +
                                       std::to_string(topology_.num_quads) + " quads exceeds 2^32 output vertices");
  positions_.reserve(quads.positions.size());
  for (const Point3& p : quads.positions) positions_.push_back(to_vec3(p));
  points_.resize(topology_);
  records_.assign(topology_.extraordinary_quads.size() * kRecordSize, Vec3f{});
  if (multithreaded_ && threads > 0) arena_ = std::make_unique<tbb::task_arena>(threads);
  build_output_topology();
  build_lane_groups();
}

// Ordinary quads in groups of kLanes for evaluate_bicubic_lanes; the last group repeats its last
// quad in the lanes left over (the same values written twice, by the same thread).
void CpatchCpuEvaluation::build_lane_groups() {
  const std::vector<int>& ordinary = topology_.ordinary_quads;
  lane_groups_.clear();
  for (size_t g = 0; g < ordinary.size(); g += kLanes)
    for (size_t l = 0; l < size_t(kLanes); ++l) lane_groups_.push_back(ordinary[std::min(g + l, ordinary.size() - 1)]);
}

void CpatchCpuEvaluation::build_output_topology() { grid_output_topology(topology_.num_quads, grid_.rate(), out_); }

void CpatchCpuEvaluation::set_positions(const std::vector<Point3>& positions) {
  if (positions.size() != positions_.size()) throw std::invalid_argument("set_positions: vertex count differs");
  for (size_t i = 0; i < positions.size(); ++i) positions_[i] = to_vec3(positions[i]);
}

// body(begin, end, scratch) over [0, count): serially, or in TBB chunks of at least `grain`.
template <class Body>
void CpatchCpuEvaluation::for_range(int count, int grain, const Body& body) {
  if (!multithreaded_) {
    body(0, count, scratch_);
    return;
  }
  auto run = [&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, count, grain),
                      [&](const tbb::blocked_range<int>& r) { body(r.begin(), r.end(), thread_scratch_.local()); });
  };
  if (arena_)
    arena_->execute(run);
  else
    run();
}

void CpatchCpuEvaluation::execute() {
  // Pass 1a, Table 1: per vertex.
  for_range(topology_.num_vertices, 1024, [&](int begin, int end, PatchScratch&) {
    converter_.convert_vertices(positions_.data(), begin, end, points_);
  });
  // Pass 1b, Table 2: per extraordinary quad, the c-patch record.
  const std::vector<int>& cpatches = topology_.extraordinary_quads;
  auto cpatch_record = [&](int e) { return &records_[static_cast<size_t>(e) * kRecordSize]; };
  for_range(static_cast<int>(cpatches.size()), 256, [&](int begin, int end, PatchScratch&) {
    for (int e = begin; e < end; ++e) converter_.build_cpatch(positions_.data(), points_, e, cpatch_record(e));
  });
  // Pass 2: per quad, N x N positions and normals; ordinary quads kLanes at a time, gathering
  // their Figure 6 data from the vertex points.
  const size_t per_quad = static_cast<size_t>(grid_.samples());
  const int groups = static_cast<int>(lane_groups_.size() / kLanes);
  for_range(groups, 16, [&](int begin, int end, PatchScratch&) {
    for (int g = begin; g < end; ++g) {
      BicubicLaneSource source{positions_.data(), &points_, {}};
      uint8_t sides[kLanes];
      Point3* positions[kLanes];
      Point3* normals[kLanes];
      for (int l = 0; l < kLanes; ++l) {
        const int q = lane_groups_[static_cast<size_t>(g) * kLanes + l];
        source.corners[l] = &topology_.corners[4 * static_cast<size_t>(q)];
        sides[l] = topology_.forward_sides[q];
        positions[l] = &out_.positions[q * per_quad];
        normals[l] = &out_.normals[q * per_quad];
      }
      evaluate_bicubic_lanes(grid_, source, sides, positions, normals);
    }
  });
  for_range(static_cast<int>(cpatches.size()), 64, [&](int begin, int end, PatchScratch& scratch) {
    for (int e = begin; e < end; ++e) {
      const int q = cpatches[e];
      evaluate_quad(grid_, cpatch_record(e), true, topology_.forward_sides[q], scratch, &out_.positions[q * per_quad],
                    &out_.normals[q * per_quad]);
    }
  });
}

PatchRecord CpatchCpuEvaluation::record(int quad) const {
  PatchRecord r;
  const int e = topology_.extraordinary_index[quad];
  if (e >= 0)
    std::copy_n(&records_[static_cast<size_t>(e) * kRecordSize], kRecordSize, r.begin());
  else
    converter_.build_bicubic(positions_.data(), points_, quad, r.data());
  return r;
}

size_t CpatchCpuEvaluation::bytes_out() const { return (out_.positions.size() + out_.normals.size()) * sizeof(Point3); }

}  // namespace sdb::cpatch
