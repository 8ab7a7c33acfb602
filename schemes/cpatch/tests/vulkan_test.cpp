// The c-patch Vulkan variants (cpatch-2pass, cpatch-1pass, cpatch-tess) against the Catmull-Clark
// limit, against the CPU, for watertightness, and in render mode. Runs on whatever device
// gpu::shared_context() picks (lavapipe here), under the validation layer (testing::VulkanTest);
// skipped without a device.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "datasets/manifest.h"
#include "harness/core/errors.h"
#include "harness/gpu/testing.h"
#include "harness/mesh/acceptance.h"
#include "harness/reference/limit_evaluator.h"
#include "harness/validate/watertight.h"
#include "schemes/cpatch/cpatch.h"
#include "schemes/cpatch/cpu.h"
#include "schemes/cpatch/vulkan.h"

using namespace sdb;
using namespace sdb::cpatch;

namespace {

constexpr GpuVariant kVariants[] = {GpuVariant::TwoPass, GpuVariant::OnePass, GpuVariant::Tessellation};

ControlMesh accepted(const std::string& name) { return accept_mesh(load_mesh(name), cpatch_2pass_info()); }

double bbox_diagonal(const std::vector<Point3>& points) { return bounds_of(points).diagonal(); }

double distance(const Point3& a, const std::array<double, 3>& b) {
  double d = 0;
  for (int k = 0; k < 3; ++k) d += (a[k] - b[k]) * (a[k] - b[k]);
  return std::sqrt(d);
}

double angle_degrees(const Point3& a, const Point3& b) {
  const double d = double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2];
  const double cx = double(a[1]) * b[2] - double(a[2]) * b[1], cy = double(a[2]) * b[0] - double(a[0]) * b[2],
               cz = double(a[0]) * b[1] - double(a[1]) * b[0];
  return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), d) * 180.0 / M_PI;
}

Tessellation gpu_output(const ControlMesh& quads, int rate, GpuVariant variant, uint64_t max_chunk_bytes = 0) {
  CpatchVulkanEvaluation eval(quads, rate, variant, max_chunk_bytes);
  eval.execute();
  return eval.result();
}

Tessellation cpu_output(const ControlMesh& quads, int rate) {
  CpatchCpuEvaluation eval(quads, rate, false);
  eval.execute();
  return eval.output();
}

// The largest rate each variant runs at on this device, of the ones asked for.
bool runs_at(GpuVariant variant, int rate) { return !vulkan_unsupported(variant, GpuMode::Evaluate, rate).has_value(); }

struct Agreement {
  double max_position = 0;  // absolute
  double max_normal_deg = 0;
  size_t identical_positions = 0, identical_normals = 0, vertices = 0;
};

Agreement compare(const Tessellation& a, const Tessellation& b) {
  Agreement r;
  r.vertices = a.positions.size();
  for (size_t k = 0; k < a.positions.size(); ++k) {
    double d = 0;
    for (int c = 0; c < 3; ++c) d += double(a.positions[k][c] - b.positions[k][c]) * (a.positions[k][c] - b.positions[k][c]);
    r.max_position = std::max(r.max_position, std::sqrt(d));
    r.max_normal_deg = std::max(r.max_normal_deg, angle_degrees(a.normals[k], b.normals[k]));
    r.identical_positions += a.positions[k] == b.positions[k];
    r.identical_normals += std::memcmp(&a.normals[k], &b.normals[k], sizeof(Point3)) == 0;
  }
  return r;
}

class CpatchVulkanTest : public gpu::testing::VulkanTest {};

}  // namespace

// All quads of a torus grid are ordinary: every variant must put every vertex on the
// Catmull-Clark limit (the bicubic B-spline), to float rounding.
TEST_F(CpatchVulkanTest, AllRegularTorusIsTheCatmullClarkLimitInEveryVariant) {
  const ControlMesh quads = accepted("torus");
  const LimitEvaluator limit(quads, SubdivisionRule::CatmullClark);
  const double diagonal = bbox_diagonal(quads.positions);
  for (GpuVariant variant : kVariants)
    for (int rate : {5, 9}) {
      if (!runs_at(variant, rate)) continue;
      const Tessellation out = gpu_output(quads, rate, variant);
      double worst = 0, worst_deg = 0;
      for (size_t k = 0; k < out.num_vertices(); ++k) {
        const LimitSample p = limit.evaluate(out.coords[k]);
        worst = std::max(worst, distance(out.positions[k], p.position));
        const Point3 n = {float(p.normal[0]), float(p.normal[1]), float(p.normal[2])};
        worst_deg = std::max(worst_deg, angle_degrees(n, out.normals[k]));
      }
      std::printf("torus %s N=%d: max distance to the CC limit %.3e of the diagonal, normal %.2e deg\n",
                  scheme_name(variant), rate, worst / diagonal, worst_deg);
      EXPECT_LE(worst, 1e-5 * diagonal) << scheme_name(variant) << " N=" << rate;
      EXPECT_LE(worst_deg, 1e-2) << scheme_name(variant) << " N=" << rate;
    }
}

// The GPU performs the CPU's float operations in the CPU's order (precise, the same weight
// tables), so positions should agree to the bit; normals go through sqrt and a division, which
// Vulkan does not require to be correctly rounded. The bound asserted is the brief's, 1e-5 of the
// diagonal; the figures printed say how close they really are. The 2-pass evaluate kernel is
// held to the bit: positions everywhere, normals on a CPU device (lavapipe's sqrt and division are IEEE's).
TEST_F(CpatchVulkanTest, VulkanOutputAgreesWithTheCpu) {
  std::vector<std::string> names = {"frog-standin", "pole7", "quadsphere"};
  if (corpus_has("crane/spot_control")) names.push_back("crane/spot_control");
  for (const std::string& name : names) {
    const ControlMesh quads = accepted(name);
    const double diagonal = bbox_diagonal(quads.positions);
    for (int rate : {2, 5, 9}) {
      const Tessellation cpu = cpu_output(quads, rate);
      for (GpuVariant variant : kVariants) {
        if (!runs_at(variant, rate)) continue;
        const Agreement a = compare(gpu_output(quads, rate, variant), cpu);
        std::printf("%s %s N=%d: %zu/%zu positions bit-identical to the cpu (max distance %.2e of the diagonal), "
                    "%zu normals bit-identical (max angle %.2e deg)\n",
                    name.c_str(), scheme_name(variant), rate, a.identical_positions, a.vertices,
                    a.max_position / diagonal, a.identical_normals, a.max_normal_deg);
        EXPECT_LE(a.max_position, 1e-5 * diagonal) << name << " " << scheme_name(variant) << " N=" << rate;
        EXPECT_LE(a.max_normal_deg, 1e-3) << name << " " << scheme_name(variant) << " N=" << rate;
        if (variant == GpuVariant::TwoPass) {  // evaluate.comp keeps evaluation.cpp's order to the bit
          EXPECT_EQ(a.identical_positions, a.vertices) << name << " N=" << rate;
          if (ctx().info().type == gpu::DeviceType::Cpu) {
            EXPECT_EQ(a.identical_normals, a.vertices) << name << " N=" << rate;
          }
        }
      }
    }
  }
}

// Outputs split over several bindings (plan_chunks with a small cap): the same output.
TEST_F(CpatchVulkanTest, ChunkedOutputIsTheSameOutput) {
  const ControlMesh quads = accepted("frog-standin");
  for (GpuVariant variant : kVariants) {
    const int rate = 9;
    if (!runs_at(variant, rate)) continue;
    const Tessellation whole = gpu_output(quads, rate, variant);
    const Tessellation chunked = gpu_output(quads, rate, variant, 256 << 10);  // 256 KiB: 5 chunks
    const Agreement a = compare(whole, chunked);
    EXPECT_EQ(a.identical_positions, a.vertices) << scheme_name(variant);
    EXPECT_EQ(a.identical_normals, a.vertices) << scheme_name(variant);
  }
}

// Both quads of every edge write the same bits (0 open edges in the exact weld), and no line
// through the surface crosses it an odd number of times.
TEST_F(CpatchVulkanTest, ClosedMeshesGiveWatertightSurfaces) {
  struct Case {
    std::string mesh;
    std::vector<int> rates;
  };
  std::vector<Case> cases = {{"pole3", {2, 5, 9, 17, 33}}, {"frog-standin", {5, 9}}};
  if (corpus_has("pmp/fandisk_quads")) cases.push_back({"pmp/fandisk_quads", {9}});
  for (const Case& c : cases) {
    const ControlMesh quads = accepted(c.mesh);
    for (GpuVariant variant : kVariants)
      for (int rate : c.rates) {
        if (!runs_at(variant, rate)) continue;
        const Tessellation out = gpu_output(quads, rate, variant);
        EXPECT_EQ(count_open_edges(out), 0) << c.mesh << " " << scheme_name(variant) << " N=" << rate;
        if (rate != 9) continue;  // rays at one rate per mesh: the weld check covers the rest
        const RayCrackReport r = ray_crack_check(out, {100000, 100000, 7});
        EXPECT_EQ(r.cracks, 0) << c.mesh << " " << scheme_name(variant) << " N=" << rate << " of " << r.rays << " rays";
      }
  }
}

// The tessellator's equal_spacing at level N - 1 samples u_i = i / (N - 1): the rounding that
// recovers (i, j) in the evaluation stage moves the coordinate by float rounding only.
TEST_F(CpatchVulkanTest, TessellatorSamplesTheUniformGrid) {
  const ControlMesh quads = accepted("pole5");
  for (int rate : {2, 5, 9, 17, 33}) {
    if (!runs_at(GpuVariant::Tessellation, rate)) continue;
    CpatchVulkanEvaluation eval(quads, rate, GpuVariant::Tessellation);
    eval.execute();
    eval.result();
    std::printf("cpatch-tess N=%d: largest |gl_TessCoord (N-1) - (i, j)| = %.3e\n", rate,
                eval.engine().tess_coord_error());
    EXPECT_LT(eval.engine().tess_coord_error(), 1e-3f) << "N=" << rate;
  }
}

TEST_F(CpatchVulkanTest, OnePassRefusesRatesBeyondTheGeometryOutputLimit) {
  const int max = onepass_max_rate(ctx().limits());
  std::printf("cpatch-1pass: largest N on %s is %d (max geometry output %u vertices, %u components)\n",
              ctx().info().name.c_str(), max, ctx().limits().max_geometry_output_vertices,
              ctx().limits().max_geometry_total_output_components);
  ASSERT_GE(max, 2);
  EXPECT_FALSE(vulkan_unsupported(GpuVariant::OnePass, GpuMode::Render, max).has_value());
  const auto why = vulkan_unsupported(GpuVariant::OnePass, GpuMode::Render, max + 1);
  ASSERT_TRUE(why.has_value());
  EXPECT_NE(why->find("geometry shader"), std::string::npos) << *why;
  EXPECT_NE(why->find(std::to_string(ctx().limits().max_geometry_total_output_components)), std::string::npos) << *why;
  const auto scheme = make_cpatch_schemes();
  EXPECT_TRUE(scheme[1]->unsupported({Backend::Vulkan, max + 1, 0}).has_value());
  EXPECT_TRUE(vulkan_unsupported(GpuVariant::Tessellation, GpuMode::Evaluate, 1000).has_value());
}

// Render mode: a frame of the torus shows the surface in the middle of the 1024 x 768 target, and
// the frame has timestamps.
TEST_F(CpatchVulkanTest, RenderModeDrawsTheTorus) {
  const ControlMesh quads = accepted("torus");
  for (GpuVariant variant : kVariants) {
    GpuOptions options;
    options.variant = variant;
    options.mode = GpuMode::Render;
    CpatchVulkan renderer(quads, 5, options);
    renderer.execute();
    const gpu::Image image = renderer.read_image();
    ASSERT_EQ(image.width, 1024u);
    ASSERT_EQ(image.height, 768u);
    // The torus seen obliquely: its ring covers the points a quarter of the way in from the sides
    // on the middle row; the corners are background (white).
    const auto background = image.pixel(0, 0);
    EXPECT_EQ(background, (std::array<uint8_t, 4>{255, 255, 255, 255}));
    int covered = 0;
    for (uint32_t x = 0; x < image.width; x += 8) covered += image.pixel(x, image.height / 2) != background;
    EXPECT_GT(covered, 10) << scheme_name(variant);
    const auto times = renderer.gpu_times();
    if (!times) continue;  // no timestamps on this queue
    EXPECT_GT(times->kernel_ms, 0.0) << scheme_name(variant);
    EXPECT_FALSE(times->passes.empty());
  }
}

// A column-major camera at `eye` looking along axis `axis` (0..5: +x, -x, +y, -y, +z, -z) with a
// 90-degree field of view: six of them see every direction.
gpu::Camera camera_inside(const Point3& eye, int axis, float aspect, float near) {
  float forward[3] = {0, 0, 0}, up[3] = {0, 1, 0};
  forward[axis / 2] = axis % 2 ? -1.0f : 1.0f;
  if (axis / 2 == 1) up[1] = 0, up[2] = 1;
  const float side[3] = {forward[1] * up[2] - forward[2] * up[1], forward[2] * up[0] - forward[0] * up[2],
                         forward[0] * up[1] - forward[1] * up[0]};
  gpu::Camera c;
  for (int i = 0; i < 3; ++i) {
    c.view[i * 4 + 0] = side[i];
    c.view[i * 4 + 1] = up[i];
    c.view[i * 4 + 2] = -forward[i];
  }
  c.view[12] = -(side[0] * eye[0] + side[1] * eye[1] + side[2] * eye[2]);
  c.view[13] = -(up[0] * eye[0] + up[1] * eye[1] + up[2] * eye[2]);
  c.view[14] = forward[0] * eye[0] + forward[1] * eye[1] + forward[2] * eye[2];
  c.view[15] = 1.0f;
  const float far = 1000.0f * near;
  c.projection[0] = 1.0f / aspect;  // tan(45 degrees) = 1
  c.projection[5] = -1.0f;
  c.projection[10] = far / (near - far);
  c.projection[11] = -1.0f;
  c.projection[14] = near * far / (near - far);
  return c;
}

// The paper's Section 6: "no pixel drop out or gaps in the rendered surface". Seen from inside a
// closed surface every pixel is covered; a background pixel is a crack the rasterizer saw through.
TEST_F(CpatchVulkanTest, RenderModeHasNoPixelDropoutsFromInside) {
  const ControlMesh quads = accepted("quadsphere");
  Point3 center{0, 0, 0};
  for (const Point3& p : quads.positions)
    for (int k = 0; k < 3; ++k) center[k] += p[k] / float(quads.positions.size());
  const float near = 1e-3f * float(bbox_diagonal(quads.positions));
  for (GpuVariant variant : kVariants)
    for (int rate : {5, 9}) {
      if (!runs_at(variant, rate)) continue;
      GpuOptions options;
      options.variant = variant;
      options.mode = GpuMode::Render;
      options.width = 256, options.height = 256;
      CpatchVulkan renderer(quads, rate, options);
      for (int axis = 0; axis < 6; ++axis) {
        renderer.set_camera(camera_inside(center, axis, 1.0f, near));
        renderer.execute();
        const gpu::Image image = renderer.read_image();
        long background = 0;
        for (uint32_t y = 0; y < image.height; ++y)
          for (uint32_t x = 0; x < image.width; ++x)
            background += image.pixel(x, y) == std::array<uint8_t, 4>{255, 255, 255, 255};
        EXPECT_EQ(background, 0) << scheme_name(variant) << " N=" << rate << " view " << axis;
      }
    }
}

TEST_F(CpatchVulkanTest, HeatMapColoursByTheGivenValues) {
  const ControlMesh quads = accepted("torus");
  GpuOptions options;
  options.mode = GpuMode::Render;
  options.heat_values.assign(quads.face_sizes.size() * 25, 1.0f);  // everything at the top of the scale: red
  options.heat_scale = 1.0f;
  CpatchVulkan renderer(quads, 5, options);
  renderer.execute();
  const gpu::Image image = renderer.read_image();
  int red = 0;
  for (uint32_t x = 0; x < image.width; x += 8) {
    const auto p = image.pixel(x, image.height / 2);
    red += p[0] > 2 * p[1] && p[0] > 2 * p[2];
  }
  EXPECT_GT(red, 10);
}

TEST_F(CpatchVulkanTest, TimesEveryPassSeparately) {
  const ControlMesh quads = accepted("frog-standin");
  CpatchVulkanEvaluation eval(quads, 9, GpuVariant::TwoPass);
  eval.execute();
  eval.result();
  const auto times = eval.gpu_times();
  if (!times) GTEST_SKIP() << "no timestamps on this queue";
  std::vector<std::string> labels;
  for (const GpuPassTime& p : times->passes) labels.push_back(p.label);
  EXPECT_EQ(labels, (std::vector<std::string>{"upload control points", "pass 1a: Table 1 per vertex",
                                              "pass 1b: Table 2 per quad", "pass 2: evaluate", "readback"}));
  EXPECT_GT(times->readback_ms, 0.0);
}
