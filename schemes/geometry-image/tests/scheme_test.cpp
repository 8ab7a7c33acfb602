// The scheme as the harness sees it: info, acceptance, prepare/execute/result, backends.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "closed_mesh.h"
#include "geometry_image.h"
#include "gpu.h"
#include "test_support.h"

using namespace sdb;
using namespace sdb::gim;
using namespace sdb::gim::testing;

namespace {

const Tessellation& run(const Scheme& scheme, const ControlMesh& mesh, Backend backend, int level,
                        std::unique_ptr<Evaluation>& keep) {
  keep = scheme.prepare(accept_mesh(mesh, scheme.info()), {backend, level, 0});
  keep->execute();
  return keep->result();
}

// Scoped environment variable.
class Env {
 public:
  Env(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    value ? setenv(name, value, 1) : unsetenv(name);
  }
  ~Env() { old_.empty() ? unsetenv(name_) : setenv(name_, old_.c_str(), 1); }

 private:
  const char* name_;
  std::string old_;
};

}  // namespace

TEST(GeometryImageScheme, DeclaresWhatItIsAndRefusesMeshesItCannotTake) {
  const auto scheme = make_geometry_image_scheme();
  const SchemeInfo& info = scheme->info();
  EXPECT_EQ(info.name, "geometry-image");
  EXPECT_EQ(info.level_kind, LevelKind::Depth);
  EXPECT_TRUE(info.accepts.closed && info.accepts.genus0 && info.accepts.manifold);
  try {
    accept_mesh(load_mesh("torus"), info);
    ADD_FAILURE() << "a torus was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("genus 1"), std::string::npos) << e.what();
  }
  try {
    accept_mesh(load_mesh("open-patch"), info);
    ADD_FAILURE() << "an open patch was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("boundary"), std::string::npos) << e.what();
  }
  // vulkan runs wherever there is a device (vulkan_test.cpp); without one it says why.
  const gpu::DeviceInfo device = gpu::probe();
  EXPECT_EQ(scheme->unsupported({Backend::Vulkan, 2, 0}).has_value(), !device.available);
  EXPECT_TRUE(scheme->unsupported({Backend::Cpu, 7, 0}));
  EXPECT_FALSE(scheme->unsupported({Backend::CpuMt, 6, 0}));
}

TEST(GeometryImageScheme, EachPassPlanIsASchemeName) {
  EXPECT_EQ(make_geometry_image_scheme()->info().name, "geometry-image");
  EXPECT_EQ(make_geometry_image_scheme({.plan = PassPlan::PerMask})->info().name, "geometry-image-permask");
  EXPECT_EQ(geometry_image_scheme_name(PassPlan::Fused), "geometry-image");
  for (PassPlan plan : {PassPlan::Fused, PassPlan::PerMask}) {
    const SchemeInfo info = make_geometry_image_scheme({.plan = plan})->info();
    EXPECT_EQ(info.backends, (std::vector<Backend>{Backend::Cpu, Backend::CpuMt, Backend::Vulkan}));
  }
}

TEST(GeometryImageScheme, SubdividesAnAnalyticImageIntoTheOpenedGrid) {
  const auto scheme = make_geometry_image_scheme();
  const ControlMesh mesh = load_mesh("gim-sphere-31");
  std::unique_ptr<Evaluation> eval;
  for (int k = 0; k <= 3; ++k) {
    const Tessellation& t = run(*scheme, mesh, Backend::Cpu, k, eval);
    const size_t n = 30 * (size_t(1) << k) + 1;
    EXPECT_EQ(t.num_vertices(), n * n);
    EXPECT_EQ(t.num_triangles(), 2 * (n - 1) * (n - 1)) << "2 (30 2^k)^2, the paper's count";
    EXPECT_EQ(t.normals.size(), n * n);
    ASSERT_EQ(t.coords.size(), n * n);
    ASSERT_TRUE(t.reference);
    EXPECT_EQ(t.reference->face_vertices, mesh.face_vertices) << "g0 is the input's own layout";
    for (const SurfaceCoord& c : t.coords) {
      ASSERT_LT(c.face, 900u);
      ASSERT_TRUE(c.u >= 0 && c.u <= 1 && c.v >= 0 && c.v <= 1);
    }
    EXPECT_EQ(eval->bytes_out(), n * n * 2 * sizeof(Point3));
    // Triangles face the way the normals point.
    long wrong = 0;
    for (size_t i = 0; i < t.triangles.size(); i += 3) {
      const Point3 &a = t.positions[t.triangles[i]], &b = t.positions[t.triangles[i + 1]],
                   &c = t.positions[t.triangles[i + 2]], &nn = t.normals[t.triangles[i]];
      const float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      const float g[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
      wrong += g[0] * nn[0] + g[1] * nn[1] + g[2] * nn[2] <= 0;
    }
    EXPECT_EQ(wrong, 0) << "level " << k;
  }
}

TEST(GeometryImageScheme, CpuAndCpuMtGiveIdenticalNumbers) {
  const ControlMesh mesh = load_mesh("gim-ellipsoid-31");
  for (PassPlan plan : {PassPlan::Fused, PassPlan::PerMask}) {
    const auto scheme = make_geometry_image_scheme({.fit_size = 0, .plan = plan});
    std::unique_ptr<Evaluation> one, many;
    const Tessellation& a = run(*scheme, mesh, Backend::Cpu, 4, one);
    const Tessellation& b = run(*scheme, mesh, Backend::CpuMt, 4, many);
    ASSERT_EQ(a.positions.size(), b.positions.size());
    long differ = 0;
    for (size_t i = 0; i < a.positions.size(); ++i)
      differ += !bits_equal(a.positions[i], b.positions[i]) || !bits_equal(a.normals[i], b.normals[i]);
    EXPECT_EQ(differ, 0);
    EXPECT_EQ(a.triangles, b.triangles);
    // Repeated execution gives the same numbers too.
    many->execute();
    for (size_t i = 0; i < a.positions.size(); ++i) ASSERT_TRUE(bits_equal(a.positions[i], many->result().positions[i]));
  }
}

TEST(GeometryImageScheme, FitsAnImageToAMeshThatIsNotOne) {
  const Env cache("SUBDIVBENCH_CACHE", test_cache_dir().c_str());
  const auto scheme = make_geometry_image_scheme({.fit_size = 17});
  std::unique_ptr<Evaluation> eval;
  const Tessellation& t = run(*scheme, load_mesh("icosphere"), Backend::Cpu, 2, eval);
  ASSERT_TRUE(t.reference);
  EXPECT_EQ(num_faces(*t.reference), 16 * 16);
  EXPECT_EQ(t.num_vertices(), 65u * 65u);
  // The icosphere has radius 1: so has the fitted surface, within its faceting.
  for (const Point3& p : t.positions) EXPECT_NEAR(std::hypot(p[0], p[1], p[2]), 1.0, 0.03);
}

TEST(GeometryImageScheme, FitSizeComesFromTheOptionsOrTheEnvironment) {
  {
    const Env unset("SUBDIVBENCH_GIM_SIZE", nullptr);
    EXPECT_EQ(resolved_fit_size({}), kDefaultFitSize);
    EXPECT_EQ(resolved_fit_size({.fit_size = 33}), 33);
  }
  {
    const Env set("SUBDIVBENCH_GIM_SIZE", "129");
    EXPECT_EQ(resolved_fit_size({}), 129);
  }
  for (const char* bad : {"64", "3", "x", "65x"}) {
    const Env set("SUBDIVBENCH_GIM_SIZE", bad);
    EXPECT_THROW(resolved_fit_size({}), InputError) << bad;
  }
}
