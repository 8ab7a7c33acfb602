#include "harness/gpu/testing.h"

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

}  // namespace sdb::gpu::testing
