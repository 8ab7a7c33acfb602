// write_pictures where the loader finds no Vulkan driver: the manifest says so, with the reason,
// and nothing else is written. The driver list is pointed nowhere before anything touches Vulkan
// (static initialization runs before main), as in harness/gpu/tests/no_device_test.cpp.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

#include "harness/gpu/testing.h"
#include "harness/pictures/pictures.h"

namespace {
const bool k_no_driver = sdb::gpu::testing::hide_vulkan_drivers();
}  // namespace

namespace sdb::pictures {
namespace {

namespace fs = std::filesystem;

TEST(PicturesWithoutDevice, ManifestSaysUnavailableWithTheReason) {
  ASSERT_TRUE(k_no_driver);
  const fs::path dir = fs::path(SDB_BINARY_DIR) / "pictures_no_device_test";
  fs::remove_all(dir);
  const PictureManifest m = write_pictures({}, dir.string());  // the default selection
  EXPECT_FALSE(m.available);
  EXPECT_EQ(m.reason.rfind("no Vulkan device", 0), 0u) << m.reason;
  EXPECT_TRUE(m.pictures.empty());

  std::ifstream in(dir / "pictures" / "pictures.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["schema"], 1);
  EXPECT_EQ(j["available"], false);
  EXPECT_EQ(j["reason"], m.reason);
  EXPECT_EQ(j["pictures"], nlohmann::json::array());
  EXPECT_FALSE(j.contains("colour_bar"));
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir / "pictures")) files += entry.is_regular_file();
  EXPECT_EQ(files, 1u);  // the manifest alone
}

}  // namespace
}  // namespace sdb::pictures
