#include "cpu.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <stdexcept>

namespace sdb::cpatch {

CpatchCpuEvaluation::CpatchCpuEvaluation(const ControlMesh& quads, int rate, bool multithreaded, int threads)
    : topology_(build_topology(quads)),
      converter_(topology_),
      grid_(rate),
      multithreaded_(multithreaded),
      scratch_(rate * rate),
      thread_scratch_([rate] { return PatchScratch(rate * rate); }) {
  positions_.reserve(quads.positions.size());
  for (const Point3& p : quads.positions) positions_.push_back(to_vec3(p));
  points_.resize(topology_);
  records_.assign(static_cast<size_t>(topology_.num_quads) * kRecordSize, Vec3f{});
  if (multithreaded_ && threads > 0) arena_ = std::make_unique<tbb::task_arena>(threads);
  build_output_topology();
}

// Per quad its own N x N vertices (row j = v index), 2 (N-1)^2 triangles counter-clockwise in
// (u, v), which is outward for the mesh's counter-clockwise quads, and each vertex's ptex coord.
void CpatchCpuEvaluation::build_output_topology() {
  const int n = grid_.rate(), per_quad = grid_.samples();
  const size_t vertices = static_cast<size_t>(topology_.num_quads) * per_quad;
  out_.positions.assign(vertices, Point3{});
  out_.normals.assign(vertices, Point3{});
  out_.coords.resize(vertices);
  out_.triangles.clear();
  out_.triangles.reserve(static_cast<size_t>(topology_.num_quads) * 6 * (n - 1) * (n - 1));
  for (int q = 0; q < topology_.num_quads; ++q) {
    const uint32_t base = static_cast<uint32_t>(q) * static_cast<uint32_t>(per_quad);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        out_.coords[base + j * n + i] = {static_cast<uint32_t>(q), static_cast<float>(i) / static_cast<float>(n - 1),
                                         static_cast<float>(j) / static_cast<float>(n - 1)};
    for (int j = 0; j + 1 < n; ++j)
      for (int i = 0; i + 1 < n; ++i) {
        const uint32_t a = base + j * n + i, b = a + 1, c = a + n + 1, d = a + n;
        out_.triangles.insert(out_.triangles.end(), {a, b, c, a, c, d});
      }
  }
}

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
    tbb::parallel_for(tbb::blocked_range<int>(0, count, grain), [&](const tbb::blocked_range<int>& r) {
      body(r.begin(), r.end(), thread_scratch_.local());
    });
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
  // Pass 1b, Figure 6 / Table 2: per quad, the record the evaluation reads.
  for_range(topology_.num_quads, 1024, [&](int begin, int end, PatchScratch&) {
    for (int q = begin; q < end; ++q) converter_.build_patch(positions_.data(), points_, q, &records_[static_cast<size_t>(q) * kRecordSize]);
  });
  // Pass 2: per quad, N x N positions and normals.
  const size_t per_quad = static_cast<size_t>(grid_.samples());
  for_range(topology_.num_quads, 64, [&](int begin, int end, PatchScratch& scratch) {
    for (int q = begin; q < end; ++q)
      evaluate_quad(grid_, &records_[static_cast<size_t>(q) * kRecordSize], topology_.extraordinary[q] != 0,
                    topology_.forward_sides[q], scratch, &out_.positions[q * per_quad], &out_.normals[q * per_quad]);
  });
}

size_t CpatchCpuEvaluation::bytes_out() const {
  return (out_.positions.size() + out_.normals.size()) * sizeof(Point3);
}

}  // namespace sdb::cpatch
