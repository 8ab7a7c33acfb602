// probe(), device choice, the context's facts, and that validation errors are counted.
#include <gtest/gtest.h>

#include <cstdio>

#include "harness/gpu/gpu.h"
#include "harness/gpu/physical_device.h"
#include "harness/gpu/testing.h"

namespace sdb::gpu {
namespace {

class ContextTest : public testing::VulkanTest {};

TEST_F(ContextTest, ProbeDescribesTheContextsDevice) {
  const DeviceInfo info = probe(ctx().info().name);
  ASSERT_TRUE(info.available) << info.reason;
  EXPECT_EQ(info.name, ctx().info().name);
  EXPECT_FALSE(info.api_version.empty());
  EXPECT_GE(info.api_version_raw, VK_API_VERSION_1_1);
  EXPECT_GT(info.limits.max_storage_buffer_range, 0u);
  EXPECT_GT(info.limits.max_memory_allocation_size, 0u);
  EXPECT_GE(info.limits.max_buffer_size, info.limits.max_memory_allocation_size);
  EXPECT_GT(info.limits.timestamp_period_ns, 0.0f);
  EXPECT_FALSE(info.devices.empty());
  std::printf("%s", describe(info).c_str());
  std::printf("summary: %s\n", summary(info).c_str());
}

TEST_F(ContextTest, ProbeOfAnAbsentDeviceSaysWhichExist) {
  const DeviceInfo info = probe("no-such-device-anywhere");
  EXPECT_FALSE(info.available);
  EXPECT_NE(info.reason.find("no-such-device-anywhere"), std::string::npos) << info.reason;
  EXPECT_NE(info.reason.find(ctx().info().name), std::string::npos) << info.reason;
}

TEST_F(ContextTest, ValidationErrorsAreCounted) {
  if (!ctx().validation_enabled()) GTEST_SKIP() << "VK_LAYER_KHRONOS_validation is not installed";
  // A context of its own, so that the deliberate error does not count against this test.
  ContextOptions options;
  options.device = ctx().info().name;
  options.validation = Validation::On;
  options.print_validation = false;
  auto own = Context::create(options);
  ASSERT_TRUE(own->validation_enabled());
  EXPECT_EQ(own->validation_errors(), 0u);
  // Recorded, never submitted: a dispatch with no pipeline bound.
  const Recording recording = own->record([&](Commands& cmd) { own->vk().vkCmdDispatch(cmd.raw(), 1, 1, 1); });
  EXPECT_GT(own->validation_errors(), 0u);
  EXPECT_FALSE(own->validation_messages().empty());
}

TEST_F(ContextTest, MissingBarriersAreCaughtBySynchronizationValidation) {
  if (!ctx().validation_enabled()) GTEST_SKIP() << "VK_LAYER_KHRONOS_validation is not installed";
  ContextOptions options;
  options.device = ctx().info().name;
  options.validation = Validation::On;
  options.sync_validation = true;
  options.print_validation = false;
  auto own = Context::create(options);
  Buffer a = Buffer::device(*own, 1024, BufferUsage::Storage, "a");
  Buffer b = Buffer::device(*own, 1024, BufferUsage::Storage, "b");
  // Recorded, never submitted: a copy reads what a fill just wrote, with no barrier between.
  const Recording recording = own->record([&](Commands& cmd) {
    cmd.fill(a, 0);
    cmd.copy(a, b);
  });
  EXPECT_GT(own->validation_errors(), 0u);
}

DeviceInfo fake(const char* name, DeviceType type, bool usable = true) {
  DeviceInfo d;
  d.name = name;
  d.type = type;
  d.available = usable;
  if (!usable) d.reason = std::string(name) + " supports Vulkan 1.0 only";
  return d;
}

TEST(ChooseDevice, PrefersDiscreteThenIntegratedThenCpu) {
  const std::vector<DeviceInfo> devices{fake("llvmpipe", DeviceType::Cpu), fake("Intel UHD", DeviceType::Integrated),
                                        fake("NVIDIA H100", DeviceType::Discrete)};
  EXPECT_EQ(choose_device(devices, "").index, 2);
  EXPECT_EQ(choose_device(std::vector(devices.begin(), devices.begin() + 2), "").index, 1);
  EXPECT_EQ(choose_device(std::vector(devices.begin(), devices.begin() + 1), "").index, 0);
}

TEST(ChooseDevice, NameOverrideIsACaseInsensitiveSubstring) {
  const std::vector<DeviceInfo> devices{fake("llvmpipe (LLVM 15)", DeviceType::Cpu),
                                        fake("NVIDIA H100", DeviceType::Discrete)};
  EXPECT_EQ(choose_device(devices, "LLVMPIPE").index, 0);
  const DeviceChoice none = choose_device(devices, "radeon");
  EXPECT_EQ(none.index, -1);
  EXPECT_NE(none.reason.find("radeon"), std::string::npos);
}

TEST(ChooseDevice, SkipsUnusableDevices) {
  const std::vector<DeviceInfo> devices{fake("old GPU", DeviceType::Discrete, false), fake("llvmpipe", DeviceType::Cpu)};
  EXPECT_EQ(choose_device(devices, "").index, 1);
  const DeviceChoice old = choose_device(devices, "old");
  EXPECT_EQ(old.index, -1);
  EXPECT_NE(old.reason.find("1.0 only"), std::string::npos);
  EXPECT_EQ(choose_device({}, "").index, -1);
}

}  // namespace
}  // namespace sdb::gpu
