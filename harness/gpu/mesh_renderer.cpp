#include "harness/gpu/mesh_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
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

// mesh_colour.vert / .frag: the same block, with the shading parameters where the colour was.
struct ColourPush {
  float mvp[16];
  float view_rows[12];
  float shading[4];
};
static_assert(sizeof(ColourPush) == 128);

template <typename Push>
void set_camera(Push& push, const Camera& camera) {
  const std::array<float, 16> mvp = multiply(camera.projection, camera.view);
  std::copy(mvp.begin(), mvp.end(), push.mvp);
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 4; ++col) push.view_rows[row * 4 + col] = camera.view[col * 4 + row];
}

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

GraphicsPipelineDesc vertex_colour_pipeline_desc() {
  GraphicsPipelineDesc d;
  d.vertex = sdb_gpu_shaders::get("mesh_colour.vert");
  d.fragment = sdb_gpu_shaders::get("mesh_colour.frag");
  d.vertex_bindings = {{12, false}, {12, false}, {12, false}};
  d.vertex_attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0},
                         {1, 1, VK_FORMAT_R32G32B32_SFLOAT, 0},
                         {2, 2, VK_FORMAT_R32G32B32_SFLOAT, 0}};
  d.push_constant_bytes = sizeof(ColourPush);
  return d;
}

void check_mesh_view(const MeshView& mesh, const char* who) {
  if (!mesh.positions || !mesh.normals || !mesh.indices)
    throw std::invalid_argument(std::string(who) + ": the mesh needs positions, normals and indices");
}

// Averages factor x factor blocks of pixels.
Image downsample(const Image& big, uint32_t factor) {
  if (factor == 1) return big;
  Image small;
  small.width = big.width / factor;
  small.height = big.height / factor;
  small.rgba.resize(size_t(small.width) * small.height * 4);
  const uint32_t samples = factor * factor;
  for (uint32_t y = 0; y < small.height; ++y)
    for (uint32_t x = 0; x < small.width; ++x)
      for (int c = 0; c < 4; ++c) {
        uint32_t sum = 0;
        for (uint32_t dy = 0; dy < factor; ++dy)
          for (uint32_t dx = 0; dx < factor; ++dx)
            sum += big.rgba[((size_t(y) * factor + dy) * big.width + size_t(x) * factor + dx) * 4 + c];
        small.rgba[(size_t(y) * small.width + x) * 4 + c] = static_cast<uint8_t>((sum + samples / 2) / samples);
      }
  return small;
}

// The largest factor up to `wanted` whose target the device can hold.
uint32_t supersample_for(const Context& ctx, const PictureOptions& o) {
  uint32_t factor = std::max(o.supersample, 1u);
  while (factor > 1 && (o.width * factor > ctx.limits().max_framebuffer_width ||
                        o.height * factor > ctx.limits().max_framebuffer_height))
    --factor;
  return factor;
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

Camera frame_points(const std::vector<Point3>& points, float aspect, const Point3& direction, float margin) {
  if (points.empty()) return frame_bounds({0, 0, 0}, {0, 0, 0}, aspect);
  const Vec3 back = normalized(direction);  // from the shape towards the eye
  if (std::abs(back[1]) > 0.999f) throw std::invalid_argument("frame_points: the view direction must not be vertical (y is up)");
  const Vec3 side = normalized(cross({0.0f, 1.0f, 0.0f}, back)), up = cross(back, side);
  // Extents in the view's axes about the first point (any origin will do): the centre of the
  // projected box is where the camera looks.
  Vec3 lo{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(), std::numeric_limits<float>::max()};
  Vec3 hi{-lo[0], -lo[1], -lo[2]};
  const Vec3 origin = points.front();
  for (const Point3& p : points) {
    const Vec3 d = sub(p, origin);
    const Vec3 v{dot(d, side), dot(d, up), dot(d, back)};
    for (int i = 0; i < 3; ++i) lo[i] = std::min(lo[i], v[i]), hi[i] = std::max(hi[i], v[i]);
  }
  const float x0 = (lo[0] + hi[0]) / 2, y0 = (lo[1] + hi[1]) / 2;
  const float depth = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-6f});
  const float fov_y = 35.0f * 3.14159265f / 180.0f;
  const float tan_y = std::tan(fov_y / 2.0f) * (1.0f - 2.0f * margin), tan_x = tan_y * aspect;
  // The eye sits at distance D in front of the box's front plane z = hi[2] from the looked-at
  // point; each point's x and y offsets over its distance to the eye must fit the field of view.
  float distance = 0;
  for (const Point3& p : points) {
    const Vec3 d = sub(p, origin);
    const float x = std::abs(dot(d, side) - x0), y = std::abs(dot(d, up) - y0), z = dot(d, back) - hi[2];
    distance = std::max({distance, x / tan_x + z, y / tan_y + z});
  }
  distance = std::max(distance, 0.01f * depth);
  const Vec3 centre{origin[0] + x0 * side[0] + y0 * up[0] + hi[2] * back[0],
                    origin[1] + x0 * side[1] + y0 * up[1] + hi[2] * back[1],
                    origin[2] + x0 * side[2] + y0 * up[2] + hi[2] * back[2]};
  const Vec3 eye{centre[0] + distance * back[0], centre[1] + distance * back[1], centre[2] + distance * back[2]};
  Camera camera;
  camera.view = look_at(eye, centre, {0.0f, 1.0f, 0.0f});
  camera.projection = perspective(fov_y, aspect, 0.9f * distance, distance + 1.1f * (hi[2] - lo[2]) + 0.01f * depth);
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
  check_mesh_view(mesh, "MeshRenderer::draw");
  MeshPush push{};
  set_camera(push, camera);
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

VertexColourRenderer::VertexColourRenderer(Context& ctx) : pipeline_(ctx, vertex_colour_pipeline_desc()) {}

void VertexColourRenderer::draw(Commands& cmd, const MeshView& mesh, const Buffer& colours, const Camera& camera,
                                float ambient, uint64_t colours_offset) const {
  check_mesh_view(mesh, "VertexColourRenderer::draw");
  ColourPush push{};
  set_camera(push, camera);
  push.shading[0] = ambient;
  cmd.bind(pipeline_);
  cmd.push(push);
  cmd.bind_vertex_buffer(0, *mesh.positions, mesh.positions_offset);
  cmd.bind_vertex_buffer(1, *mesh.normals, mesh.normals_offset);
  cmd.bind_vertex_buffer(2, colours, colours_offset);
  cmd.bind_index_buffer(*mesh.indices, mesh.indices_offset);
  cmd.draw_indexed(mesh.index_count);
}

Image render_image(Context& ctx, const Tessellation& tess, const std::vector<Point3>& vertex_colours,
                   const PictureOptions& options) {
  if (vertex_colours.size() != tess.positions.size())
    throw std::invalid_argument("render_image: " + std::to_string(vertex_colours.size()) + " colours for " +
                                std::to_string(tess.positions.size()) + " vertices");
  const uint32_t factor = supersample_for(ctx, options);
  RenderTarget target(ctx, options.width * factor, options.height * factor);
  const GpuMesh mesh = upload_mesh(ctx, tess);
  const Buffer colours = device_buffer_with(ctx, vertex_colours, BufferUsage::Vertex, "vertex colours");
  const VertexColourRenderer renderer(ctx);
  const Camera camera = options.camera ? *options.camera : frame_tessellation(tess, target.aspect());
  Buffer pixels = Buffer::readback(ctx, target.pixel_bytes(), "rendered pixels");
  ctx.run([&](Commands& cmd) {
    target.render(
        cmd, [&](Commands& c) { renderer.draw(c, mesh.view(), colours, camera, options.ambient); }, options.background);
    target.download(cmd, pixels);
  });
  return downsample(target.to_image(pixels), factor);
}

}  // namespace sdb::gpu

