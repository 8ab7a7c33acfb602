#include "harness/gpu/testing.h"

#include <cmath>
#include <cstdlib>

#include <cstdio>
#include <memory>

#include "harness/gpu/errors.h"

namespace sdb::gpu::testing {

namespace {

struct State {
  bool tried = false;
  std::shared_ptr<Context> context;
  std::string reason;
  int ran = 0;
};

State& state() {
  static State s;
  return s;
}

// Prints how many Vulkan tests ran, and tears the context down before static destruction.
class VulkanEnvironment : public ::testing::Environment {
 public:
  void TearDown() override {
    State& s = state();
    if (s.context)
      std::printf("vulkan tests run on %s: %d\n", s.context->info().name.c_str(), s.ran);
    else if (s.tried)
      std::printf("vulkan tests run on no device: 0 (%s)\n", s.reason.c_str());
    s.context.reset();
    release_shared_context();
  }
};

::testing::Environment* const environment = ::testing::AddGlobalTestEnvironment(new VulkanEnvironment);

}  // namespace

Context* test_context() {
  State& s = state();
  if (!s.tried) {
    s.tried = true;
    ContextOptions options;
    options.validation = Validation::On;
    options.sync_validation = true;
    try {
      s.context = shared_context(options);
    } catch (const std::exception& e) {
      s.reason = e.what();
    }
  }
  return s.context.get();
}

const std::string& unavailable_reason() { return state().reason; }

uint64_t begin_vulkan_test() {
  Context* ctx = test_context();
  return ctx ? ctx->validation_errors() : 0;
}

void end_vulkan_test(uint64_t errors_before) {
  Context* ctx = test_context();
  if (!ctx) return;
  const uint64_t errors = ctx->validation_errors() - errors_before;
  if (errors > 0) {
    std::string messages;
    for (const std::string& m : ctx->validation_messages()) messages += "\n  " + m;
    ADD_FAILURE() << errors << " Vulkan validation error(s) during this test:" << messages;
  }
  if (!::testing::Test::IsSkipped()) ++state().ran;
}

void VulkanTest::SetUp() {
  ctx_ = test_context();
  if (!ctx_) GTEST_SKIP() << unavailable_reason();
  errors_before_ = begin_vulkan_test();
}

void VulkanTest::TearDown() {
  if (ctx_) end_vulkan_test(errors_before_);
}

bool hide_vulkan_drivers() {
  unsetenv("VK_DRIVER_FILES");  // it would take precedence over VK_ICD_FILENAMES
  unsetenv("VK_ADD_DRIVER_FILES");
  return setenv("VK_ICD_FILENAMES", "/nonexistent", 1) == 0;
}

Tessellation uv_sphere(int rings, int segments, const Point3& centre, float radius) {
  Tessellation t;
  const float pi = 3.14159265f;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      const float theta = pi * float(r) / float(rings), phi = 2 * pi * float(s) / float(segments);
      const Point3 n{std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
      t.normals.push_back(n);
      t.positions.push_back({centre[0] + radius * n[0], centre[1] + radius * n[1], centre[2] + radius * n[2]});
    }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const uint32_t a = r * (segments + 1) + s, b = a + segments + 1;
      t.triangles.insert(t.triangles.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  return t;
}

}  // namespace sdb::gpu::testing
