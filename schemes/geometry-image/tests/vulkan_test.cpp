// The Vulkan passes against the CPU's: padded levels, positions and normals per vertex, both pass
// plans; the cut symmetry on the device; chunked outputs; timestamps; the scheme's vulkan backend.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>

#include "harness/gpu/testing.h"
#include "harness/mesh/acceptance.h"
#include "schemes/geometry-image/analytic.h"
#include "schemes/geometry-image/closed_mesh.h"
#include "schemes/geometry-image/geometry_image.h"
#include "schemes/geometry-image/subdivision.h"
#include "schemes/geometry-image/tests/limit_comparison.h"
#include "schemes/geometry-image/tests/test_support.h"
#include "schemes/geometry-image/vulkan_subdivider.h"

using namespace sdb;
using namespace sdb::gim;
using namespace sdb::gim::testing;

namespace {

class GeometryImageVulkan : public gpu::testing::VulkanTest {};

struct Frame {
  std::vector<Point3> positions, normals;
};

Frame cpu_frame(const ControlMesh& g0, Subdivider& s) {
  const size_t n = static_cast<size_t>(s.size(s.levels()));
  Frame f{std::vector<Point3>(n * n), std::vector<Point3>(n * n)};
  s.run(g0.positions.data(), f.positions.data(), f.normals.data(), SerialRows());
  return f;
}

Frame vulkan_frame(const ControlMesh& g0, VulkanSubdivider& s) {
  const size_t n = static_cast<size_t>(s.size(s.levels()));
  Frame f{std::vector<Point3>(n * n), std::vector<Point3>(n * n)};
  s.run(g0.positions.data());
  s.read_back(f.positions.data(), f.normals.data());
  return f;
}

const char* plan_name(PassPlan plan) { return plan == PassPlan::Fused ? "fused" : "per-mask"; }

struct Agreement {
  long vertices = 0, positions_identical = 0, normals_identical = 0;
  double position_max = 0;    // of the bounding-box diagonal
  double normal_max_deg = 0;  // angle between the CPU's and the device's normal
};

double angle_deg(const Point3& a, const Point3& b) {
  const double cosine = double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2];
  const double sine = std::hypot(double(a[1]) * b[2] - double(a[2]) * b[1], double(a[2]) * b[0] - double(a[0]) * b[2],
                                 double(a[0]) * b[1] - double(a[1]) * b[0]);
  return std::atan2(sine, cosine) * 180.0 / M_PI;
}

Agreement compare(const Frame& cpu, const Frame& gpu) {
  Agreement a;
  const double diag = diagonal(cpu.positions);
  a.vertices = static_cast<long>(cpu.positions.size());
  for (size_t v = 0; v < cpu.positions.size(); ++v) {
    const Point3 &p = cpu.positions[v], &q = gpu.positions[v];
    a.positions_identical += bits_equal(p, q);
    a.normals_identical += bits_equal(cpu.normals[v], gpu.normals[v]);
    a.position_max =
        std::max(a.position_max, std::hypot(double(p[0]) - q[0], double(p[1]) - q[1], double(p[2]) - q[2]) / diag);
    a.normal_max_deg = std::max(a.normal_max_deg, angle_deg(cpu.normals[v], gpu.normals[v]));
  }
  return a;
}

long padded_differences(const PaddedImage& a, const PaddedImage& b) {
  long differ = 0;
  for (size_t i = 0; i < a.data.size(); ++i)
    differ += std::bit_cast<uint32_t>(a.data[i]) != std::bit_cast<uint32_t>(b.data[i]);
  return differ;
}

// Vertices whose position or normal differs in its bits between two frames of the same grid.
long frame_differences(const Frame& a, const Frame& b) {
  long differ = 0;
  for (size_t v = 0; v < a.positions.size(); ++v)
    differ += !bits_equal(a.positions[v], b.positions[v]) || !bits_equal(a.normals[v], b.normals[v]);
  return differ;
}

}  // namespace

TEST(GeometryImageShaderConstants, OneThirtySixthHasTheBitsTheShaderUses) {
  // output_grid.glsl spells 1.0f / 36.0f by its bits.
  EXPECT_EQ(std::bit_cast<uint32_t>(1.0f / 36.0f), 0x3ce38e39u);
}

TEST_F(GeometryImageVulkan, MatchesTheCpuPassForPassAndVertexForVertex) {
  struct Case {
    const char* name;
    GeometryImage image;
    int max_level;
  };
  const Case cases[] = {{"ellipsoid 31x31", analytic_image(AnalyticShape::Ellipsoid, 31), 4},
                        {"wobbly 17x17", wobbly_image(17), 4}};
  for (const Case& c : cases) {
    const ControlMesh g0 = closed_mesh(c.image, "g0", "test");
    for (PassPlan plan : {PassPlan::Fused, PassPlan::PerMask})
      for (int k = 0; k <= c.max_level; ++k) {
        Subdivider cpu(c.image.size, k, plan);
        VulkanSubdivider gpu(ctx(), c.image.size, k, plan);
        const Frame a = cpu_frame(g0, cpu), b = vulkan_frame(g0, gpu);
        long level_bits_differ = 0;
        for (int j = 0; j <= k; ++j) level_bits_differ += padded_differences(cpu.level(j), gpu.level(j));
        const Agreement r = compare(a, b);
        std::printf(
            "  %-16s %-8s k=%d: padded levels %ld floats differ; positions %ld/%ld bit-identical, max %.2e of "
            "the diagonal; normals %ld/%ld bit-identical, max %.2e deg\n",
            c.name, plan_name(plan), k, level_bits_differ, r.positions_identical, r.vertices, r.position_max,
            r.normals_identical, r.vertices, r.normal_max_deg);
        // Vulkan rounds float32 addition and multiplication correctly and every sum is `precise`
        // in the CPU's order: the positions are the CPU's bits on any conformant device. (Built with
        // spirv-opt's -O, the shaders lost `precise` on unrolled copies of the limit mask: three of
        // every four vertices came out 1-2 ulp off; cmake/Shaders.cmake.)
        EXPECT_EQ(r.positions_identical, r.vertices) << c.name << " " << plan_name(plan) << " k=" << k;
        EXPECT_EQ(level_bits_differ, 0) << c.name << " " << plan_name(plan) << " k=" << k;
        EXPECT_LE(r.position_max, 1e-5) << c.name << " " << plan_name(plan) << " k=" << k;
        EXPECT_LE(r.normal_max_deg, 1e-3) << c.name << " " << plan_name(plan) << " k=" << k;
      }
  }
}

TEST_F(GeometryImageVulkan, KeepsTheCutSymmetryBitForBitOnTheDevice) {
  const GeometryImage image = wobbly_image(17);
  const ControlMesh g0 = closed_mesh(image, "g0", "test");
  for (PassPlan plan : {PassPlan::Fused, PassPlan::PerMask}) {
    const int k = 3;
    VulkanSubdivider gpu(ctx(), image.size, k, plan);
    const Frame f = vulkan_frame(g0, gpu);
    for (int j = 0; j <= k; ++j)
      EXPECT_EQ(padded_symmetry_violations(gpu.level(j)), 0) << plan_name(plan) << ", padded g^" << j;
    const int n = gpu.size(k);
    EXPECT_EQ(grid_symmetry_violations(f.positions, n), 0) << plan_name(plan) << ": positions";
    // Normals too: identical inputs to the division and square root, and -0 cleared on the bits.
    EXPECT_EQ(grid_symmetry_violations(f.normals, n), 0) << plan_name(plan) << ": normals";
    for (const Point3& q : f.normals) ASSERT_NEAR(std::hypot(q[0], q[1], q[2]), 1.0, 1e-5) << plan_name(plan);
  }
}

TEST_F(GeometryImageVulkan, ChunkedOutputsEqualOneBinding) {
  const GeometryImage image = wobbly_image(17);
  const ControlMesh g0 = closed_mesh(image, "g0", "test");
  for (PassPlan plan : {PassPlan::Fused, PassPlan::PerMask}) {
    VulkanSubdivider whole(ctx(), image.size, 3, plan);
    // 129 x 129 vertices, 200 KB of positions: binding 16 KiB at a time makes more than a dozen
    // chunks of whole rows, so that the cut vertices fall into different chunks.
    VulkanSubdivider chunked(ctx(), image.size, 3, plan, {.max_output_chunk_bytes = 16 << 10});
    ASSERT_EQ(whole.output_chunks(), 1u);
    ASSERT_GT(chunked.output_chunks(), 4u);
    EXPECT_EQ(frame_differences(vulkan_frame(g0, whole), vulkan_frame(g0, chunked)), 0)
        << plan_name(plan) << " in " << chunked.output_chunks() << " chunks";
    std::printf("  %s: %zu output chunks, bit-identical to one binding\n", plan_name(plan), chunked.output_chunks());
  }
}

// Images past one storage binding (2 GiB of texel view against 128 MiB of binding on lavapipe)
// are written through rgba32f texel views instead of storage buffers: the same bits.
TEST_F(GeometryImageVulkan, TexelViewDestinationsEqualStorageBuffers) {
  const GeometryImage image = wobbly_image(17);
  const ControlMesh g0 = closed_mesh(image, "g0", "test");
  for (PassPlan plan : {PassPlan::Fused, PassPlan::PerMask}) {
    VulkanSubdivider buffers(ctx(), image.size, 3, plan);
    VulkanSubdivider texels(ctx(), image.size, 3, plan, {.max_image_binding_bytes = 4 << 10});
    ASSERT_FALSE(buffers.texel_destinations());
    ASSERT_TRUE(texels.texel_destinations());
    EXPECT_EQ(frame_differences(vulkan_frame(g0, buffers), vulkan_frame(g0, texels)), 0) << plan_name(plan);
    for (int k = 0; k <= 3; ++k) {
      const PaddedImage la = buffers.level(k), lb = texels.level(k);
      ASSERT_EQ(la.data.size(), lb.data.size());
      EXPECT_EQ(padded_differences(la, lb), 0) << plan_name(plan) << ": g^" << k;
    }
  }
}

TEST_F(GeometryImageVulkan, RepeatedFramesGiveTheSameBits) {
  const GeometryImage image = analytic_image(AnalyticShape::Sphere, 31);
  const ControlMesh g0 = closed_mesh(image, "g0", "test");
  VulkanSubdivider gpu(ctx(), image.size, 2, PassPlan::Fused);
  const Frame a = vulkan_frame(g0, gpu);
  const Frame b = vulkan_frame(g0, gpu);
  for (size_t v = 0; v < a.positions.size(); ++v) {
    ASSERT_TRUE(bits_equal(a.positions[v], b.positions[v])) << v;
    ASSERT_TRUE(bits_equal(a.normals[v], b.normals[v])) << v;
  }
}

TEST_F(GeometryImageVulkan, TimestampsArePresentAndOrdered) {
  const GeometryImage image = analytic_image(AnalyticShape::Sphere, 31);
  const ControlMesh g0 = closed_mesh(image, "g0", "test");
  const std::vector<std::string> fused = {"upload", "pad", "L+A 1", "L+A 2", "E+T", "cut-vertex normals", "readback"};
  const std::vector<std::string> per_mask = {
      "upload", "pad", "L 1", "A 1", "L 2", "A 2", "E", "T", "cut-vertex normals", "readback"};
  for (PassPlan plan : {PassPlan::Fused, PassPlan::PerMask}) {
    VulkanSubdivider gpu(ctx(), image.size, 2, plan);
    vulkan_frame(g0, gpu);
    const auto passes = gpu.timestamps();
    if (!passes) GTEST_SKIP() << ctx().info().name << " has no timestamps on this queue";
    std::vector<std::string> labels;
    for (const auto& p : *passes) labels.push_back(p.label);
    EXPECT_EQ(labels, plan == PassPlan::Fused ? fused : per_mask);
    for (size_t i = 0; i < passes->size(); ++i) {
      const gpu::PassTimestamps& p = (*passes)[i];
      EXPECT_LE(p.begin_ticks, p.end_ticks) << p.label;
      EXPECT_GE(p.ms, 0.0) << p.label;
      if (i > 0) {
        EXPECT_GE(p.begin_ticks, (*passes)[i - 1].end_ticks) << p.label << " begins before the pass before it ends";
      }
    }
    const auto times = gpu.times();
    ASSERT_TRUE(times);
    EXPECT_EQ(times->passes.size(), passes->size());
    EXPECT_GT(times->kernel_ms, 0.0);
    EXPECT_EQ(times->passes.front().label, "upload");
    EXPECT_EQ(times->passes.back().label, "readback");
  }
}

TEST_F(GeometryImageVulkan, TheSchemeRunsOnVulkanWithBothPlans) {
  const ControlMesh mesh = load_mesh("gim-ellipsoid-31");
  for (PassPlan plan : {PassPlan::Fused, PassPlan::PerMask}) {
    const auto scheme = make_geometry_image_scheme(plan);
    EXPECT_EQ(scheme->info().name, plan == PassPlan::Fused ? "geometry-image" : "geometry-image-permask");
    EXPECT_FALSE(scheme->unsupported({Backend::Vulkan, 4, 0}));
    auto cpu = scheme->prepare(accept_mesh(mesh, scheme->info()), default_request(scheme->info(), Backend::Cpu, 3));
    auto gpu = scheme->prepare(accept_mesh(mesh, scheme->info()), default_request(scheme->info(), Backend::Vulkan, 3));
    cpu->execute();
    gpu->execute();
    const Tessellation &a = cpu->result(), &b = gpu->result();
    EXPECT_EQ(a.triangles, b.triangles);
    ASSERT_EQ(b.coords.size(), a.coords.size());
    ASSERT_TRUE(b.reference);
    EXPECT_EQ(b.reference->face_vertices, a.reference->face_vertices);
    EXPECT_EQ(gpu->bytes_out(), cpu->bytes_out());
    const Agreement r = compare({a.positions, a.normals}, {b.positions, b.normals});
    EXPECT_LE(r.position_max, 1e-5) << plan_name(plan);
    const auto times = gpu->gpu_times();
    ASSERT_TRUE(times) << "timestamps through Evaluation::gpu_times()";
    EXPECT_GT(times->upload_ms + times->kernel_ms + times->readback_ms, 0.0);
    // A second frame without a result() in between is read back on the next result().
    gpu->execute();
    EXPECT_EQ(compare({a.positions, a.normals}, {gpu->result().positions, gpu->result().normals}).position_max,
              r.position_max);
  }
}

TEST_F(GeometryImageVulkan, RefusesWhatTheDeviceCannotHoldWithTheReason) {
  // 2049 x 2049 at depth 6: padded images of 131,075^2 vec4, past any device's largest buffer.
  const auto why = VulkanSubdivider::unsupported(ctx(), 2049, 6, PassPlan::Fused);
  ASSERT_TRUE(why);
  EXPECT_NE(why->find("allocates at most"), std::string::npos) << *why;
  EXPECT_THROW(VulkanSubdivider(ctx(), 2049, 6, PassPlan::Fused), gpu::Unsupported);
  EXPECT_FALSE(VulkanSubdivider::unsupported(ctx(), 31, 4, PassPlan::PerMask));
}
