// The cache of fitted images (creation/cache.h) is trusted for nothing: a file that is not what
// was written (NaN, infinities or zeros, samples scaled or shifted, truncated, a flipped bit,
// another mesh's image under this key) is refused with the reason, the image refitted and the
// refit written over it; the scheme's row says so.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>

#include "harness/core/registry.h"
#include "harness/images/image_io.h"
#include "schemes/geometry-image/tests/test_support.h"

using namespace sdb;
using namespace sdb::gim;
using namespace sdb::gim::testing;
namespace fs = std::filesystem;

namespace {

CreationOptions options_in(const std::string& dir) {
  CreationOptions options;
  options.size = 9;
  options.cache_dir = dir;
  return options;
}

// The cached file's samples changed by `change`, written back with the header it had (key, size,
// checksum and figures): what a disk error, an editor or another program could leave.
std::function<void(const std::string&)> samples_changed(std::function<void(float&)> change) {
  return [change](const std::string& path) {
    std::optional<images::FloatImage> image = images::image_codec().read_float(path, 9, 9, 3);
    ASSERT_TRUE(image);
    for (float& v : image->samples) change(v);
    ASSERT_TRUE(images::image_codec().write_float(*image, path, "zip"));
  };
}

void rewrite_bytes(const std::string& path, const std::function<void(std::string&)>& change) {
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  change(bytes);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

struct Tampering {
  std::string name, reason;  // the reason the refusal must give
  std::function<void(const std::string& path)> apply;
};

}  // namespace

TEST(ImageCache, RefusesEveryFileThatIsNotWhatWasWrittenAndRefits) {
  const std::string dir = test_cache_dir() + "/tampered";
  fs::remove_all(dir);
  const ControlMesh mesh = load_mesh("pole5");
  const CreatedImage fresh = create_geometry_image(mesh, options_in(dir));
  ASSERT_FALSE(fresh.report.cache_path.empty());
  const std::string path = fresh.report.cache_path;
  ControlMesh other = load_mesh("pole5");
  other.positions[0][0] += 0.25f;
  const std::string other_path = create_geometry_image(other, options_in(dir)).report.cache_path;
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const std::vector<Tampering> tamperings = {
      {"NaN", "is not a finite number", samples_changed([nan](float& v) { v = nan; })},
      {"infinities", "is not a finite number", samples_changed([inf](float& v) { v = -inf; })},
      {"zeros", "checksum mismatch", samples_changed([](float& v) { v = 0; })},
      {"scaled by 2", "checksum mismatch", samples_changed([](float& v) { v *= 2; })},
      {"shifted", "checksum mismatch", samples_changed([](float& v) { v += 0.5f; })},
      {"truncated", "unreadable", [](const std::string& p) { rewrite_bytes(p, [](std::string& b) { b.resize(b.size() / 2); }); }},
      {"a flipped bit", "", [](const std::string& p) { rewrite_bytes(p, [](std::string& b) { b[b.size() - 40] ^= 0x10; }); }},
      {"another mesh's image", "written for another key", [&](const std::string& p) { fs::copy_file(other_path, p, fs::copy_options::overwrite_existing); }},
      {"a link", "not a regular file", [&](const std::string& p) { fs::remove(p); fs::create_symlink(other_path, p); }},
  };
  for (const Tampering& t : tamperings) {
    ASSERT_TRUE(create_geometry_image(mesh, options_in(dir)).report.from_cache) << "the untouched file is used";
    t.apply(path);
    const CreatedImage again = create_geometry_image(mesh, options_in(dir));
    EXPECT_FALSE(again.report.from_cache) << t.name << ": a tampered cache file was used";
    EXPECT_NE(again.report.cache_refused.find(path), std::string::npos) << t.name << ": " << again.report.cache_refused;
    EXPECT_NE(again.report.cache_refused.find(t.reason), std::string::npos) << t.name << ": " << again.report.cache_refused;
    ASSERT_EQ(again.image.samples.size(), fresh.image.samples.size());
    for (size_t i = 0; i < fresh.image.samples.size(); ++i)
      ASSERT_TRUE(bits_equal(again.image.samples[i], fresh.image.samples[i])) << t.name << ": the refit differs at " << i;
    std::printf("  %-22s refused: %s\n", t.name.c_str(), again.report.cache_refused.c_str());
  }
  EXPECT_TRUE(create_geometry_image(mesh, options_in(dir)).report.from_cache) << "the refit was not cached again";
  fs::remove_all(dir);
}

TEST(ImageCache, TheSchemesRowSaysItRefittedARefusedFile) {
  const std::string dir = test_cache_dir() + "/noted";
  fs::remove_all(dir);
  setenv("SUBDIVBENCH_CACHE", dir.c_str(), 1);
  const ControlMesh mesh = load_mesh("pole5");
  const Scheme& scheme = *find_scheme("geometry-image");
  RunRequest request = default_request(scheme.info(), Backend::Cpu, 1);
  EXPECT_TRUE(scheme.prepare(mesh, request)->notes().empty()) << "a first fit is no news";
  const std::string path = create_geometry_image(mesh, [&] {
                             CreationOptions o;
                             o.size = request.parameters.integer("fit");
                             return o;
                           }()).report.cache_path;
  ASSERT_TRUE(fs::exists(path));
  rewrite_bytes(path, [](std::string& b) { b.resize(b.size() / 3); });
  const std::vector<std::string> notes = scheme.prepare(mesh, request)->notes();
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("cached geometry image refused (" + path + ": unreadable"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("): refitted"), std::string::npos) << notes[0];
  EXPECT_TRUE(scheme.prepare(mesh, request)->notes().empty()) << "the refit was cached again";
  unsetenv("SUBDIVBENCH_CACHE");
  fs::remove_all(dir);
}
