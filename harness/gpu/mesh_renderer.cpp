#include "harness/gpu/mesh_renderer.h"

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>

#include "sdb_gpu_shaders.h"

namespace sdb::gpu {

namespace {

using Vec3 = std::array<float, 3>;

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
float dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3 normalized(const Vec3& a) {
  const float n = std::sqrt(dot(a, a));
  return {a[0] / n, a[1] / n, a[2] / n};
}

// Right-handed look-at: the camera looks down its -z.
std::array<float, 16> look_at(const Vec3& eye, const Vec3& centre, const Vec3& up) {
  const Vec3 f = normalized(sub(centre, eye));
  const Vec3 s = normalized(cross(f, up));
  const Vec3 u = cross(s, f);
  std::array<float, 16> m{};
  for (int i = 0; i < 3; ++i) {
    m[i * 4 + 0] = s[i];
    m[i * 4 + 1] = u[i];
    m[i * 4 + 2] = -f[i];
  }
  m[12] = -dot(s, eye);
  m[13] = -dot(u, eye);
  m[14] = dot(f, eye);
  m[15] = 1.0f;
  return m;
}

// Vulkan clip space: y flipped, depth from 0 at `near` to 1 at `far`.
std::array<float, 16> perspective(float fov_y, float aspect, float near, float far) {
  const float f = 1.0f / std::tan(fov_y / 2.0f);
  std::array<float, 16> m{};
  m[0] = f / aspect;
  m[5] = -f;
  m[10] = far / (near - far);
  m[11] = -1.0f;
  m[14] = near * far / (near - far);
  return m;
}

// Matches the push-constant block of mesh.vert / mesh.frag (128 bytes, the guaranteed minimum).
struct MeshPush {
  float mvp[16];
  float view_rows[12];
  float colour[4];
};
static_assert(sizeof(MeshPush) == 128);

GraphicsPipelineDesc mesh_pipeline_desc(bool wireframe) {
  GraphicsPipelineDesc d;
  d.vertex = sdb_gpu_shaders::get("mesh.vert");
  d.fragment = sdb_gpu_shaders::get("mesh.frag");
  d.vertex_bindings = {{12, false}, {12, false}};
  d.vertex_attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0}, {1, 1, VK_FORMAT_R32G32B32_SFLOAT, 0}};
  d.push_constant_bytes = sizeof(MeshPush);
  d.wireframe = wireframe;
  return d;
}

}  // namespace

std::array<float, 16> multiply(const std::array<float, 16>& a, const std::array<float, 16>& b) {
  std::array<float, 16> m{};
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row) {
      float sum = 0.0f;
      for (int k = 0; k < 4; ++k) sum += a[k * 4 + row] * b[col * 4 + k];
      m[col * 4 + row] = sum;
    }
  return m;
}

Camera frame_bounds(const Point3& lo, const Point3& hi, float aspect) {
  const Vec3 centre{(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
  float radius = std::sqrt(dot(sub(hi, lo), sub(hi, lo))) / 2;
  if (!(radius > 0.0f)) radius = 1.0f;
  const float fov_y = 35.0f * 3.14159265f / 180.0f;
  const float fov_x = 2.0f * std::atan(aspect * std::tan(fov_y / 2.0f));
  const float distance = 1.05f * radius / std::sin(std::min(fov_y, fov_x) / 2.0f);
  const Vec3 direction = normalized({0.55f, 0.45f, 1.0f});
  const Vec3 eye{centre[0] + distance * direction[0], centre[1] + distance * direction[1],
                 centre[2] + distance * direction[2]};
  Camera camera;
  camera.view = look_at(eye, centre, {0.0f, 1.0f, 0.0f});
  const float near = std::max(distance - 1.1f * radius, 0.01f * distance);
  camera.projection = perspective(fov_y, aspect, near, distance + 1.1f * radius);
  return camera;
}

Camera frame_tessellation(const Tessellation& tess, float aspect) {
  Point3 lo{0, 0, 0}, hi{0, 0, 0};
  if (!tess.positions.empty()) lo = hi = tess.positions.front();
  for (const Point3& p : tess.positions)
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  return frame_bounds(lo, hi, aspect);
}

GpuMesh upload_mesh(Context& ctx, const Tessellation& tess) {
  if (tess.positions.empty() || tess.triangles.empty())
    throw std::invalid_argument("upload_mesh: the tessellation has no vertices or no triangles");
  if (tess.normals.size() != tess.positions.size())
    throw std::invalid_argument("upload_mesh: the tessellation has " + std::to_string(tess.normals.size()) +
                                " normals for " + std::to_string(tess.positions.size()) + " vertices");
  GpuMesh mesh;
  mesh.positions = device_buffer_with(ctx, tess.positions, BufferUsage::Vertex | BufferUsage::Storage,
                                      "mesh positions");
  mesh.normals = device_buffer_with(ctx, tess.normals, BufferUsage::Vertex | BufferUsage::Storage,
                                    "mesh normals");
  mesh.indices = device_buffer_with(ctx, tess.triangles, BufferUsage::Index | BufferUsage::Storage,
                                    "mesh indices");
  mesh.index_count = static_cast<uint32_t>(tess.triangles.size());
  return mesh;
}

MeshRenderer::MeshRenderer(Context& ctx, bool wireframe) : pipeline_(ctx, mesh_pipeline_desc(wireframe)) {}

void MeshRenderer::draw(Commands& cmd, const MeshView& mesh, const Camera& camera, std::array<float, 3> colour) const {
  if (!mesh.positions || !mesh.normals || !mesh.indices)
    throw std::invalid_argument("MeshRenderer::draw: the mesh needs positions, normals and indices");
  MeshPush push{};
  const std::array<float, 16> mvp = multiply(camera.projection, camera.view);
  std::copy(mvp.begin(), mvp.end(), push.mvp);
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 4; ++col) push.view_rows[row * 4 + col] = camera.view[col * 4 + row];
  push.colour[0] = colour[0];
  push.colour[1] = colour[1];
  push.colour[2] = colour[2];
  push.colour[3] = 1.0f;
  cmd.bind(pipeline_);
  cmd.push(push);
  cmd.bind_vertex_buffer(0, *mesh.positions, mesh.positions_offset);
  cmd.bind_vertex_buffer(1, *mesh.normals, mesh.normals_offset);
  cmd.bind_index_buffer(*mesh.indices, mesh.indices_offset);
  cmd.draw_indexed(mesh.index_count);
}

Image render_image(Context& ctx, const Tessellation& tess, uint32_t width, uint32_t height) {
  RenderTarget target(ctx, width, height);
  const GpuMesh mesh = upload_mesh(ctx, tess);
  const MeshRenderer renderer(ctx);
  const Camera camera = frame_tessellation(tess, target.aspect());
  Buffer pixels = Buffer::readback(ctx, target.pixel_bytes(), "rendered pixels");
  ctx.run([&](Commands& cmd) {
    target.render(cmd, [&](Commands& c) { renderer.draw(c, mesh.view(), camera); });
    target.download(cmd, pixels);
  });
  return target.to_image(pixels);
}

}  // namespace sdb::gpu

