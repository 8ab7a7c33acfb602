// Where the loader finds no driver: probe() says so in one line and nothing crashes.
// This binary points the loader at a driver list that does not exist before anything touches
// Vulkan (static initialization runs before main).
#include <gtest/gtest.h>


#include "harness/gpu/gpu.h"
#include "harness/gpu/loader.h"
#include "harness/gpu/testing.h"

namespace {
const bool k_no_driver = sdb::gpu::testing::hide_vulkan_drivers();
}  // namespace

namespace sdb::gpu {
namespace {

TEST(NoDevice, ProbeReportsUnavailableWithTheReason) {
  ASSERT_TRUE(k_no_driver);
  const DeviceInfo info = probe();
  EXPECT_FALSE(info.available);
  EXPECT_EQ(info.reason.rfind("no Vulkan device", 0), 0u) << info.reason;
  EXPECT_NE(info.reason.find("VK_ICD_FILENAMES=/nonexistent"), std::string::npos) << info.reason;
  EXPECT_EQ(info.reason.find('\n'), std::string::npos);
  EXPECT_EQ(summary(info), info.reason);
  std::printf("probe: %s\n", info.reason.c_str());
}

TEST(NoDevice, ContextCreationThrowsUnavailable) {
  EXPECT_THROW(Context::create(), Unavailable);
  EXPECT_THROW(shared_context(), Unavailable);
}

class NoDeviceVulkanTest : public testing::VulkanTest {};

TEST_F(NoDeviceVulkanTest, IsSkipped) { FAIL() << "a Vulkan test ran without a device"; }

TEST(NoLoader, MissingLibraryIsReportedInOneLine) {
  const LoaderStatus status = open_loader("libvulkan-does-not-exist.so.1");
  EXPECT_EQ(status.get_instance_proc_addr, nullptr);
  EXPECT_EQ(status.reason, "no Vulkan loader (libvulkan-does-not-exist.so.1 not found)");
}

}  // namespace
}  // namespace sdb::gpu
