#include "schemes/cpatch/vulkan_resources.h"

#include <algorithm>
#include <stdexcept>

namespace sdb::cpatch {
namespace {

gpu::Buffer storage(gpu::Context& ctx, uint64_t bytes, const char* name) {
  gpu::check_storage_binding(ctx, bytes, name);
  return gpu::Buffer::device(ctx, std::max<uint64_t>(bytes, 16), gpu::BufferUsage::Storage, name);
}

uint64_t float3_bytes(size_t count) { return count * 3 * sizeof(float); }

}  // namespace

std::vector<float> grid_table(const SampleGrid& grid) {
  const int n = grid.rate(), samples = grid.samples();
  std::vector<float> table(4 * (2 * n + 12 * static_cast<size_t>(samples)), 0.0f);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 4; ++k) {
      table[4 * i + k] = grid.cubic(k)[i];
      table[4 * (n + i) + k] = grid.cubic_du(k)[i];
    }
  const float* tables[3] = {grid.quartic(0), grid.quartic_du(0), grid.quartic_dv(0)};
  for (int sorted = 0; sorted < samples; ++sorted) {
    const int s = grid.piece_order()[sorted];
    for (int t = 0; t < 3; ++t)
      for (int m = 0; m < kQuarticPoints; ++m)
        table[4 * (2 * n + 12 * size_t(s) + 4 * t) + m] = tables[t][m * samples + sorted];
  }
  return table;
}

std::vector<uint32_t> quad_info_table(const CpatchTopology& t) {
  std::vector<uint32_t> info(t.num_quads);
  for (int q = 0; q < t.num_quads; ++q)
    info[q] = uint32_t(t.forward_sides[q]) | (uint32_t(t.extraordinary_index[q] + 1) << 4);
  return info;
}

EvaluateRuns evaluate_runs(const CpatchTopology& t, const gpu::ChunkPlan& plan, uint64_t samples_per_quad) {
  EvaluateRuns r;
  for (size_t k = 0; k < plan.chunks.size(); ++k) {
    const uint64_t first = plan.chunks[k].first_element / samples_per_quad;
    const uint64_t end = first + plan.chunks[k].elements / samples_per_quad;
    for (bool cpatch : {false, true}) {
      EvaluateRun run{k, cpatch, static_cast<uint32_t>(first), static_cast<uint32_t>(r.lists.size()), 0};
      for (uint64_t q = first; q < end; ++q)
        if ((t.extraordinary_index[q] >= 0) == cpatch) r.lists.push_back(uint32_t(q) << 4 | t.forward_sides[q]);
      run.count = static_cast<uint32_t>(r.lists.size() - run.list_offset);
      if (run.count > 0) r.runs.push_back(run);
    }
  }
  return r;
}

uint64_t DeviceMesh::bytes_needed(const CpatchTopology& t, const SampleGrid& grid, bool intermediates) {
  uint64_t bytes = 2 * float3_bytes(t.num_vertices) + (t.first_slot.size() + t.ring.size()) * sizeof(int) +
                   t.corners.size() * sizeof(QuadCorner) + t.num_quads * sizeof(uint32_t) +
                   t.cpatch_weights.size() * sizeof(CpatchCornerWeights) + grid_table(grid).size() * sizeof(float);
  if (intermediates)
    bytes += float3_bytes(t.num_vertices) + 3 * float3_bytes(t.num_slots()) + size_t(t.num_quads) * kRecordSize * 4 * sizeof(float);
  return bytes;
}

DeviceMesh::DeviceMesh(gpu::Context& ctx, const CpatchTopology& t, const SampleGrid& sample_grid, bool intermediates) {
  const uint64_t control_bytes = float3_bytes(t.num_vertices);
  control_staging = gpu::Buffer::upload(ctx, control_bytes, "c-patch control points (staging)");
  control_points = storage(ctx, control_bytes, "c-patch control points");
  first_slot = gpu::storage_table(ctx, t.first_slot, "c-patch first_slot");
  ring = gpu::storage_table(ctx, t.ring, "c-patch ring");
  valence_constants = gpu::storage_table(ctx, t.valence_constants, "c-patch valence constants");
  std::vector<float> trig_pairs;
  for (size_t j = 0; j < t.trig_cos.size(); ++j) trig_pairs.insert(trig_pairs.end(), {t.trig_cos[j], t.trig_sin[j]});
  trig = gpu::storage_table(ctx, trig_pairs, "c-patch cos/sin table");
  corners = gpu::storage_table(ctx, t.corners, "c-patch quad corners");
  quad_info = gpu::storage_table(ctx, quad_info_table(t), "c-patch quad info");
  corner_weights = gpu::storage_table(ctx, t.cpatch_weights, "c-patch Table 2 weights");
  // Storage for the graphics variants' stages, a texel buffer for the evaluate pass (fetches
  // are vector gathers on lavapipe).
  grid = gpu::device_buffer_with(ctx, grid_table(sample_grid), gpu::BufferUsage::Storage | gpu::BufferUsage::UniformTexel,
                                 "c-patch grid weights");
  if (!intermediates) return;
  limit_points = storage(ctx, control_bytes, "c-patch limit points");
  face_points = storage(ctx, float3_bytes(t.num_slots()), "c-patch face points");
  edge_points = storage(ctx, float3_bytes(t.num_slots()), "c-patch edge points");
  tangent_points = storage(ctx, float3_bytes(t.num_slots()), "c-patch tangent points");
  const uint64_t record_bytes = size_t(t.num_quads) * kRecordSize * 4 * sizeof(float);
  gpu::check_storage_binding(ctx, record_bytes, "c-patch patch records");
  records = gpu::Buffer::device(ctx, record_bytes, gpu::BufferUsage::Storage | gpu::BufferUsage::UniformTexel,
                                "c-patch patch records");
}

void DeviceMesh::write_positions(const std::vector<Vec3f>& positions) const {
  static_assert(sizeof(Vec3f) == 3 * sizeof(float));
  control_staging.write(positions.data(), float3_bytes(positions.size()));
}

void DeviceMesh::record_upload(gpu::Commands& cmd) const { cmd.upload(control_staging, control_points); }

DeviceOutput::DeviceOutput(gpu::Context& ctx, int num_quads, int rate, uint32_t local_size, uint64_t max_chunk_bytes)
    : samples_(uint64_t(rate) * rate) {
  plan_ = gpu::plan_chunks(ctx.limits(), {uint64_t(num_quads) * samples_, 12, samples_, local_size, max_chunk_bytes});
  for (uint64_t bytes : plan_.buffer_bytes) {
    const gpu::BufferUsage usage = gpu::BufferUsage::Storage;
    positions_.push_back(gpu::Buffer::device(ctx, bytes, usage, "c-patch output positions"));
    normals_.push_back(gpu::Buffer::device(ctx, bytes, usage, "c-patch output normals"));
    positions_staging_.push_back(gpu::Buffer::readback(ctx, bytes, "c-patch output positions (readback)"));
    normals_staging_.push_back(gpu::Buffer::readback(ctx, bytes, "c-patch output normals (readback)"));
  }
}

void DeviceOutput::record_download(gpu::Commands& cmd) const {
  for (size_t b = 0; b < positions_.size(); ++b) {
    cmd.download(positions_[b], positions_staging_[b]);
    cmd.download(normals_[b], normals_staging_[b]);
  }
}

void DeviceOutput::read(Tessellation& out) const {
  static_assert(sizeof(Point3) == 12);
  // Chunks are contiguous within a buffer, and buffers follow each other in element order.
  uint64_t element = 0;
  for (size_t b = 0; b < positions_.size(); ++b) {
    const uint64_t bytes = plan_.buffer_bytes[b];
    positions_staging_[b].read(&out.positions[element], bytes);
    normals_staging_[b].read(&out.normals[element], bytes);
    element += bytes / 12;
  }
}

}  // namespace sdb::cpatch
