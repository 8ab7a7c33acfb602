// The c-patch schemes on Vulkan (README.md, "Vulkan"): cpatch-2pass (compute conversion, then
// evaluation in a compute pass or in the vertex stage), cpatch-1pass (vertex stage Table 1,
// geometry stage Table 2 + evaluation) and cpatch-tess (vertex stage Table 1, tessellation
// control stage Table 2, tessellator + evaluation stage).
//
// Two modes: Evaluate writes positions and normals to buffers (the harness's timed
// Evaluation::execute(), read back in result()); Render rasterizes the surface into a 1024 x 768
// offscreen target (the paper's pipeline, timed for frames per second).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/scheme.h"
#include "harness/gpu/gpu.h"
#include "schemes/cpatch/evaluation.h"
#include "schemes/cpatch/topology.h"
#include "schemes/cpatch/vec3.h"

namespace sdb::cpatch {

struct EvaluateRun;  // vulkan_resources.h

enum class GpuVariant { TwoPass, OnePass, Tessellation };
enum class GpuMode { Evaluate, Render };
const char* scheme_name(GpuVariant variant);  // "cpatch-2pass", ...

// The 1-pass geometry shader emits 2 N (N - 1) vertices of this many components (clip position
// and view normal) per quad; shader variants are built for N up to kOnePassCompiledRate.
constexpr int kOnePassComponents = 7;
constexpr int kOnePassCompiledRate = 11;  // glslang caps max_vertices at 256: 2 N (N - 1) <= 256
// The largest N whose geometry output fits the device's maxGeometryOutputVertices and
// maxGeometryTotalOutputComponents (9 on lavapipe and on NVIDIA's 1024 / 1024; the paper had 8
// under DX10).
int onepass_max_rate(const gpu::DeviceLimits& limits);

// Why `variant` cannot run at rate N on the shared device (no device, a missing stage, a limit),
// or nullopt. Mesh-dependent limits (memory) are checked when a CpatchVulkan is made.
std::optional<std::string> vulkan_unsupported(GpuVariant variant, GpuMode mode, int rate);

struct GpuOptions {
  GpuVariant variant = GpuVariant::TwoPass;
  GpuMode mode = GpuMode::Evaluate;
  uint32_t width = 1024, height = 768;  // the render target (render mode)
  // Render mode, 2-pass only: colour each output vertex by heat_values[k] / heat_scale on a
  // blue-white-red scale (deviation heat maps).
  std::vector<float> heat_values;
  float heat_scale = 1.0f;
  // Render mode: the camera; by default one that frames the control mesh's bounding box.
  std::optional<gpu::Camera> camera;
  // Evaluate mode: a smaller output chunk than one storage binding (0: the device's limit), to
  // exercise the chunked path on small meshes in tests.
  uint64_t max_chunk_bytes = 0;
};

class CpatchVulkan {
 public:
  // `quads`: a closed manifold all-quad mesh (accept_mesh() output); throws InputError when the
  // conversion refuses it, gpu::Unsupported beyond the device's limits or memory.
  CpatchVulkan(const ControlMesh& quads, int rate, const GpuOptions& options);
  ~CpatchVulkan();
  CpatchVulkan(const CpatchVulkan&) = delete;
  CpatchVulkan& operator=(const CpatchVulkan&) = delete;

  // Render mode: the camera of the next frames (blocking upload).
  void set_camera(const gpu::Camera& camera);
  // Replaces the control positions (same count) for the next frame.
  void set_positions(const std::vector<Point3>& positions);
  // One frame: upload, conversion, evaluation (and rasterization in render mode); waits.
  void execute();
  // Evaluate mode, after execute(): reads positions and normals back into `out` (laid out by
  // grid_output_topology()).
  void read_output(Tessellation& out);
  // Render mode, after execute(): the frame.
  gpu::Image read_image();
  // Timestamps of the last execute() and, if it ran after it, of read_output().
  std::optional<GpuTimes> gpu_times() const;
  // cpatch-tess, evaluate mode, after read_output(): the largest |gl_TessCoord (N-1) - (i, j)|.
  float tess_coord_error() const { return tess_coord_error_; }

  const CpatchTopology& topology() const { return topology_; }
  int rate() const { return grid_.rate(); }
  const GpuOptions& options() const { return options_; }
  gpu::Context& context() const { return *ctx_; }

 private:
  struct Device;  // buffers, pipelines, descriptor sets, recordings (vulkan.cpp)
  void record_frame();
  void record_conversion(gpu::Commands& cmd);
  void record_two_pass_evaluation(gpu::Commands& cmd);
  void record_evaluate_run(gpu::Commands& cmd, const EvaluateRun& run, bool border_rows) const;
  void record_corner_draw(gpu::Commands& cmd);
  void record_readback();

  std::shared_ptr<gpu::Context> ctx_;
  CpatchTopology topology_;
  SampleGrid grid_;
  GpuOptions options_;
  std::vector<Vec3f> positions_;
  std::unique_ptr<Device> device_;
  bool read_since_execute_ = false;
  float tess_coord_error_ = 0.0f;
};

// The `vulkan` backend of cpatch-2pass, cpatch-1pass and cpatch-tess: evaluate mode.
class CpatchVulkanEvaluation final : public Evaluation {
 public:
  CpatchVulkanEvaluation(const ControlMesh& quads, int rate, GpuVariant variant, uint64_t max_chunk_bytes = 0);
  void execute() override;
  const Tessellation& result() override;
  size_t bytes_out() const override;
  std::optional<GpuTimes> gpu_times() const override { return gpu_.gpu_times(); }
  CpatchVulkan& engine() { return gpu_; }

 private:
  CpatchVulkan gpu_;
  Tessellation out_;
  bool read_ = false;
};

}  // namespace sdb::cpatch
