// GoogleTest support for tests that need a Vulkan device, for this module and for schemes.
//
//   class MyTest : public sdb::gpu::testing::VulkanTest {};
//   TEST_F(MyTest, Works) { sdb::gpu::Context& c = ctx(); ... }
//
// A VulkanTest is skipped, with the reason, when there is no device; it fails when the
// validation layer reports an error during the test. The context is gpu::shared_context(),
// created with validation on (when the layer is installed), so scheme code that calls
// shared_context() runs under the same checks. At the end the binary prints
// "vulkan tests run on <device>: N" (or why none ran).
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>

#include "harness/core/tessellation.h"
#include "harness/gpu/context.h"

namespace sdb::gpu::testing {

// The shared context, created on first use for tests; null when there is no device.
Context* test_context();
const std::string& unavailable_reason();

// For tests that run Vulkan work in some of their cases only (a parameterized suite): call
// begin_vulkan_test() at the start of such a case (it returns the context's validation error
// count) and end_vulkan_test() at its end, which fails the test on new validation errors and
// counts it in "vulkan tests run on <device>: N". VulkanTest does the same.
uint64_t begin_vulkan_test();
void end_vulkan_test(uint64_t errors_before);

// Points the Vulkan loader at a driver list that does not exist, so that this process finds no
// device. Call it in a static initializer, before anything touches Vulkan; false if it failed.
bool hide_vulkan_drivers();

// A UV sphere of `radius` around `centre`, with exact normals: the renderer tests' subject.
Tessellation uv_sphere(int rings, int segments, const Point3& centre = {0, 0, 0}, float radius = 1);
// The renderer's background.
inline bool is_white(const std::array<uint8_t, 4>& p) { return p[0] == 255 && p[1] == 255 && p[2] == 255; }

class VulkanTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  Context& ctx() { return *ctx_; }

 private:
  Context* ctx_ = nullptr;
  uint64_t errors_before_ = 0;
};

}  // namespace sdb::gpu::testing
