// Device buffers of the c-patch Vulkan variants (README.md, "Vulkan"): what prepare() uploads
// once (topology tables, the SampleGrid's weights), the control points refreshed every frame, the
// 2-pass scheme's intermediate buffers, and the evaluate-only output split by gpu::plan_chunks.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "harness/core/tessellation.h"
#include "harness/gpu/gpu.h"
#include "schemes/cpatch/evaluation.h"
#include "schemes/cpatch/topology.h"
#include "schemes/cpatch/vec3.h"

namespace sdb::cpatch {

// The SampleGrid's tables as the shaders read them (evaluate.glsl), in vec4s: (B_0..B_3)(u_i) at
// vec4 i, their derivatives at vec4 N + i, then for every grid sample s = j N + i the 15 quartic
// weights (padded to 16) of the c-patch piece holding s: position at vec4 2 N + 12 s, d/du at
// + 4, d/dv at + 8. The same floats as the CPU's tables (re-indexed by grid sample instead of
// piece order).
std::vector<float> grid_table(const SampleGrid& grid);

// Per quad: bits 0-3 forward_sides, bits 4.. the c-patch index + 1 (0: ordinary); record.glsl.
std::vector<uint32_t> quad_info_table(const CpatchTopology& t);

// The evaluate pass's dispatches: per output chunk, its ordinary quads, then its c-patches, each
// a run of EvaluateRuns::lists entries (quad << 4 | forward_sides).
struct EvaluateRun {
  size_t chunk = 0;
  bool cpatch = false;
  uint32_t first_quad = 0;   // the chunk's
  uint32_t list_offset = 0;  // in the lists
  uint32_t count = 0;
};
struct EvaluateRuns {
  std::vector<uint32_t> lists;
  std::vector<EvaluateRun> runs;  // none empty
};
// Per chunk and per kind (bicubic, c-patch), in quad order.
EvaluateRuns evaluate_runs(const CpatchTopology& t, const gpu::ChunkPlan& plan, uint64_t samples_per_quad);

class DeviceMesh {
 public:
  // `intermediates`: the 2-pass scheme's VertexPoints and PatchRecord buffers as well.
  DeviceMesh(gpu::Context& ctx, const CpatchTopology& t, const SampleGrid& grid, bool intermediates);

  static uint64_t bytes_needed(const CpatchTopology& t, const SampleGrid& grid, bool intermediates);
  void write_positions(const std::vector<Vec3f>& positions) const;  // into the staging buffer
  void record_upload(gpu::Commands& cmd) const;                     // staging -> control points

  gpu::Buffer control_staging, control_points;
  gpu::Buffer first_slot, ring, valence_constants, trig, corners, quad_info, corner_weights, grid;
  gpu::Buffer limit_points, face_points, edge_points, tangent_points, records;  // 2-pass only
};

// The evaluate-only output: float3 positions and normals of num_quads x N^2 vertices, in chunks
// that fit one storage binding, each a whole number of quads.
class DeviceOutput {
 public:
  DeviceOutput(gpu::Context& ctx, int num_quads, int rate, uint32_t local_size, uint64_t max_chunk_bytes = 0);

  // Bytes of one array (positions or normals).
  static uint64_t array_bytes(int num_quads, int rate) { return uint64_t(num_quads) * rate * rate * 12; }
  const gpu::ChunkPlan& plan() const { return plan_; }
  gpu::BufferRange positions(const gpu::Chunk& c) const { return positions_[c.buffer].range(c.byte_offset, c.bytes); }
  gpu::BufferRange normals(const gpu::Chunk& c) const { return normals_[c.buffer].range(c.byte_offset, c.bytes); }
  uint32_t first_quad(const gpu::Chunk& c) const { return static_cast<uint32_t>(c.first_element / samples_); }
  uint32_t quads(const gpu::Chunk& c) const { return static_cast<uint32_t>(c.elements / samples_); }

  void record_download(gpu::Commands& cmd) const;
  // After the download ran: the arrays into `out` (sized by grid_output_topology()).
  void read(Tessellation& out) const;

 private:
  gpu::ChunkPlan plan_;
  uint64_t samples_;
  std::vector<gpu::Buffer> positions_, normals_, positions_staging_, normals_staging_;
};

}  // namespace sdb::cpatch
