// Drawing a Tessellation (or a scheme's own position/normal/index buffers) into a RenderTarget:
// headlight Lambert shading on the normals, two-sided, and a camera that frames the bounding box;
// in one colour, or in a colour per vertex (the report's deviation pictures).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "harness/core/tessellation.h"
#include "harness/gpu/buffer.h"
#include "harness/gpu/commands.h"
#include "harness/gpu/context.h"
#include "harness/gpu/image.h"
#include "harness/gpu/pipeline.h"
#include "harness/gpu/render_target.h"

namespace sdb::gpu {

// Column-major 4x4 matrices; Vulkan clip space (y down, depth 0..1).
struct Camera {
  std::array<float, 16> view{};
  std::array<float, 16> projection{};
};

// Looks at the box's centre from a fixed oblique direction (y up), far enough that its bounding
// sphere fits a 35-degree vertical field of view (and the horizontal one when aspect < 1).
Camera frame_bounds(const Point3& lo, const Point3& hi, float aspect);
Camera frame_tessellation(const Tessellation& tess, float aspect);
// Looks at the points from `direction` (towards the eye; y up) and frames their projection, not
// their bounding sphere: the picture's edges keep a `margin` share of its size free, and the
// shape fills the rest in one of the two directions.
Camera frame_points(const std::vector<Point3>& points, float aspect, const Point3& direction, float margin = 0.05f);
std::array<float, 16> multiply(const std::array<float, 16>& a, const std::array<float, 16>& b);

// Buffers to draw: float3 positions and float3 unit normals, tightly packed (12-byte stride),
// and uint32 triangle indices. The buffers need Vertex (positions, normals) and Index usage.
struct MeshView {
  const Buffer* positions = nullptr;
  const Buffer* normals = nullptr;
  const Buffer* indices = nullptr;
  uint32_t index_count = 0;
  uint64_t positions_offset = 0;
  uint64_t normals_offset = 0;
  uint64_t indices_offset = 0;
};

struct GpuMesh {
  Buffer positions, normals, indices;
  uint32_t index_count = 0;
  MeshView view() const { return {&positions, &normals, &indices, index_count}; }
};

// Device buffers holding the tessellation (blocking upload). std::invalid_argument when normals
// or triangles are missing.
GpuMesh upload_mesh(Context& ctx, const Tessellation& tess);

class MeshRenderer {
 public:
  explicit MeshRenderer(Context& ctx, bool wireframe = false);
  // Inside RenderTarget::begin/end.
  void draw(Commands& cmd, const MeshView& mesh, const Camera& camera,
            std::array<float, 3> colour = {0.80f, 0.72f, 0.60f}) const;

 private:
  GraphicsPipeline pipeline_;
};

// The same shading on a colour per vertex: float3 RGB in [0, 1], tightly packed, one per vertex
// of the mesh drawn, in a buffer with Vertex usage.
class VertexColourRenderer {
 public:
  explicit VertexColourRenderer(Context& ctx);
  // Inside RenderTarget::begin/end. `ambient`: the share of its colour a face seen edge-on keeps.
  void draw(Commands& cmd, const MeshView& mesh, const Buffer& colours, const Camera& camera,
            float ambient = 0.25f, uint64_t colours_offset = 0) const;

 private:
  GraphicsPipeline pipeline_;
};

// One picture for reports: uploads, renders on white and reads back (blocking).
Image render_image(Context& ctx, const Tessellation& tess, uint32_t width = 1024, uint32_t height = 768);

struct PictureOptions {
  uint32_t width = 1024;
  uint32_t height = 768;
  // Rendered this many times larger and averaged down: smooth silhouettes without a multisampled
  // target. Lowered where the device's framebuffer is smaller.
  uint32_t supersample = 2;
  ClearColour background = k_white;
  float ambient = 0.25f;
  std::optional<Camera> camera;  // default: frame_tessellation
};

// One picture with a colour per vertex (RGB in [0, 1], one per tess.positions), framed as
// render_image frames it. std::invalid_argument when the counts differ.
Image render_image(Context& ctx, const Tessellation& tess, const std::vector<Point3>& vertex_colours,
                   const PictureOptions& options = {});

}  // namespace sdb::gpu
