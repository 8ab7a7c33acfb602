// The scheme as the harness sees it: info, acceptance, prepare/execute/result, backends.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "harness/gpu/gpu.h"
#include "harness/mesh/acceptance.h"
#include "schemes/geometry-image/closed_mesh.h"
#include "schemes/geometry-image/geometry_image.h"
#include "schemes/geometry-image/tests/test_support.h"

using namespace sdb;
using namespace sdb::gim;
using namespace sdb::gim::testing;

namespace {

// `parameters`: as the command line spells them after the scheme's name, e.g. ":fit=17".
const Tessellation& run(const Scheme& scheme, const ControlMesh& mesh, Backend backend, int level,
                        std::unique_ptr<Evaluation>& keep, const std::string& parameters = "") {
  RunRequest request = default_request(scheme.info(), backend, level);
  request.parameters = Parameters::resolve(scheme.info().parameters, parse_scheme_spec(scheme.info().name + parameters));
  keep = scheme.prepare(accept_mesh(mesh, scheme.info()), request);
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
  EXPECT_EQ(make_geometry_image_scheme(PassPlan::PerMask)->info().name, "geometry-image-permask");
  EXPECT_EQ(geometry_image_scheme_name(PassPlan::Fused), "geometry-image");
  for (PassPlan plan : {PassPlan::Fused, PassPlan::PerMask}) {
    const SchemeInfo info = make_geometry_image_scheme(plan)->info();
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
    const auto scheme = make_geometry_image_scheme(plan);
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
  const auto scheme = make_geometry_image_scheme();
  std::unique_ptr<Evaluation> eval;
  const Tessellation& t = run(*scheme, load_mesh("icosphere"), Backend::Cpu, 2, eval, ":fit=17");
  ASSERT_TRUE(t.reference);
  EXPECT_EQ(num_faces(*t.reference), 16 * 16);
  EXPECT_EQ(t.num_vertices(), 65u * 65u);
  // The icosphere has radius 1: so has the fitted surface, within its faceting.
  for (const Point3& p : t.positions) EXPECT_NEAR(std::hypot(p[0], p[1], p[2]), 1.0, 0.03);
}

// The fit size is a typed parameter on the request (`--scheme geometry-image:fit=129`), odd,
// 5..513, 65 by default; the estimate of the output follows it.
TEST(GeometryImageScheme, FitSizeIsATypedParameter) {
  const auto scheme = make_geometry_image_scheme();
  const auto& declared = scheme->info().parameters;
  ASSERT_EQ(declared.size(), 1u);
  EXPECT_EQ(Parameters::defaults(declared).integer("fit"), kDefaultFitSize);
  EXPECT_EQ(Parameters::resolve(declared, parse_scheme_spec("geometry-image:fit=129")).integer("fit"), 129);
  for (const char* bad : {"geometry-image:fit=64", "geometry-image:fit=3", "geometry-image:fit=x", "geometry-image:fit=515", "geometry-image:fit=1025"})
    EXPECT_THROW(Parameters::resolve(declared, parse_scheme_spec(bad)), InputError) << bad;
  const ControlMesh ico = accept_mesh(load_mesh("icosphere"), scheme->info());
  RunRequest request = default_request(scheme->info(), Backend::Cpu, 2);
  EXPECT_EQ(scheme->estimated_triangles(ico, request), 2L * 256 * 256);
  request.parameters = Parameters::resolve(declared, parse_scheme_spec("geometry-image:fit=17"));
  EXPECT_EQ(scheme->estimated_triangles(ico, request), 2L * 64 * 64);
}
