// The report's pictures: the colour map, the default selection read from the registry, the level
// chosen for a picture, and write_pictures on the Vulkan device there is (small pictures, low
// levels, so that lavapipe draws them in a second or two).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "datasets/manifest.h"
#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/gpu/image.h"
#include "harness/gpu/testing.h"
#include "harness/mesh/acceptance.h"
#include "harness/pictures/colour_map.h"
#include "harness/pictures/framing.h"
#include "harness/pictures/pictures.h"

namespace sdb::pictures {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(SDB_BINARY_DIR) / "pictures_test" / name;
  fs::remove_all(dir);
  return dir;
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

bool is_png(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  char signature[8] = {};
  in.read(signature, 8);
  return in && std::string(signature, 8) == "\x89PNG\r\n\x1a\n";
}

double luminance(const Point3& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

TEST(ColourMap, RunsFromDarkPurpleToYellowGettingBrighter) {
  const Point3 low = viridis(0), high = viridis(1);
  EXPECT_GT(low[2], low[1]);   // purple: blue over green
  EXPECT_GT(high[0], high[2]);  // yellow: red and green over blue
  for (int i = 0; i < 100; ++i) EXPECT_LT(luminance(viridis(i / 100.0f)), luminance(viridis((i + 1) / 100.0f))) << i;
  EXPECT_EQ(viridis(-1), low);
  EXPECT_EQ(viridis(NAN), low);
  EXPECT_EQ(viridis(7), high);
}

TEST(ColourMap, BarRunsLeftToRightInsideAFrame) {
  const gpu::Image bar = colour_bar(200, 20);
  ASSERT_EQ(bar.width, 200u);
  ASSERT_EQ(bar.height, 20u);
  const auto left = bar.pixel(1, 10), right = bar.pixel(198, 10), frame = bar.pixel(0, 10);
  EXPECT_NEAR(left[0], 68, 1);  // viridis(0) = (0.267, 0.005, 0.329)
  EXPECT_NEAR(right[1], 231, 1);  // viridis(1) = (0.993, 0.906, 0.144)
  EXPECT_EQ(frame[0], frame[1]);
  EXPECT_EQ(frame[1], frame[2]);
}

TEST(DefaultSelection, ThePaperSchemesOnePerPaperAndRule) {
  const std::vector<std::string> schemes = default_schemes();
  for (const char* name : {"cpatch-2pass", "geometry-image", "fragments-cc", "fragments-loop"})
    EXPECT_NE(std::find(schemes.begin(), schemes.end(), name), schemes.end()) << name;
  // Variants of the same surface, and schemes without a cpu backend, are left out.
  for (const char* name : {"geometry-image-permask", "cpatch-1pass", "cpatch-tess"})
    EXPECT_EQ(std::find(schemes.begin(), schemes.end(), name), schemes.end()) << name;
  for (const std::string& name : schemes) EXPECT_EQ(find_scheme(name)->info().role, SchemeRole::Method) << name;
  const std::vector<std::string> meshes = default_meshes();
  ASSERT_EQ(meshes.size(), 3u);
  EXPECT_EQ(meshes[1], "frog-standin");
  EXPECT_EQ(meshes[2], "icosphere");
  for (const std::string& mesh : meshes) EXPECT_NO_THROW(load_mesh(mesh)) << mesh;
}

TEST(PictureLevel, OutputNearTwoHundredThousandTriangles) {
  const ControlMesh cube = load_mesh("cube");  // 6 quads
  for (const char* name : {"fragments-cc", "cpatch-2pass"}) {
    const Scheme& scheme = *find_scheme(name);
    const ControlMesh accepted = accept_mesh(cube, scheme.info());
    const Parameters parameters = Parameters::resolve(scheme.info().parameters, parse_scheme_spec(name));
    const int level = picture_level(scheme, accepted, parameters);
    const long triangles = scheme.estimated_triangles(accepted, {Backend::Cpu, level, 0, parameters});
    EXPECT_GE(triangles, 100000) << name << " level " << level;
    EXPECT_LE(triangles, 300000) << name << " level " << level;
  }
  // Depth 7 on six quads: 6 x 2 x 4^7 = 196,608 triangles (depth 6: 49,152; depth 8: 786,432).
  const Scheme& fragments = *find_scheme("fragments-cc");
  EXPECT_EQ(picture_level(fragments, accept_mesh(cube, fragments.info()), {}), 7);
}

// A box 8 long in x, 1 by 1 across, as twelve triangles.
Tessellation long_box() {
  Tessellation t;
  for (int i = 0; i < 8; ++i) t.positions.push_back({i & 1 ? 8.0f : 0.0f, i & 2 ? 1.0f : 0.0f, i & 4 ? 1.0f : 0.0f});
  t.normals = t.positions;  // not read
  t.triangles = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
  return t;
}

TEST(Framing, ALongShapeIsSeenFromItsSide) {
  const Point3 d = view_direction(long_box());
  // Across the long axis, from above the horizon: its long faces show, not its square ends.
  EXPECT_LT(std::abs(d[0]), 0.3f);
  EXPECT_GT(std::abs(d[2]), 0.8f);
  EXPECT_GT(d[1], 0.3f);
  // A cube shows as much from every side: the renderer's default view stays.
  Tessellation cube = long_box();
  for (Point3& p : cube.positions) p[0] /= 8;
  const Point3 c = view_direction(cube);
  EXPECT_NEAR(c[0] / c[2], 0.55, 1e-3);
  EXPECT_NEAR(c[1] / c[2], 0.45, 1e-3);
}

TEST(WritePictures, BadRequestsThrowBeforeWritingAnything) {
  const fs::path dir = fresh_dir("bad");
  PictureRequest request;
  request.meshes = {"cube"};
  request.schemes = {"no-such-scheme"};
  EXPECT_THROW(write_pictures(request, dir.string()), InputError);
  request.schemes = {"cpatch-1pass"};  // vulkan only: no cpu tessellation to draw
  EXPECT_THROW(write_pictures(request, dir.string()), InputError);
  request.schemes = {"fragments-cc"};
  request.meshes = {"no-such-mesh"};
  EXPECT_THROW(write_pictures(request, dir.string()), InputError);
  request.meshes = {"cube"};
  request.width = 0;
  EXPECT_THROW(write_pictures(request, dir.string()), InputError);
  EXPECT_FALSE(fs::exists(dir));
}

class WritePicturesOnDevice : public gpu::testing::VulkanTest {};

TEST_F(WritePicturesOnDevice, ManifestListsPngsOfTheStatedSize) {
  const fs::path dir = fresh_dir("small");
  PictureRequest request;
  request.schemes = {"cpatch-2pass", "fragments-loop"};
  request.meshes = {"cube", "icosphere"};
  request.level = 3;
  request.width = 160, request.height = 120;
  std::vector<std::string> seen;
  const PictureManifest m =
      write_pictures(request, dir.string(), [&](const PictureEntry& e) { seen.push_back(e.scheme + " " + e.mesh + " " + e.kind); });
  ASSERT_TRUE(m.available) << m.reason;
  // cpatch-2pass on both meshes (the icosphere quadrangulated); fragments-loop on triangles only.
  EXPECT_EQ(seen.size(), 6u);
  ASSERT_EQ(m.notes.size(), 1u);
  EXPECT_NE(m.notes[0].find("fragments-loop cannot take mesh 'cube'"), std::string::npos) << m.notes[0];

  const nlohmann::json j = read_json(dir / "pictures" / "pictures.json");
  EXPECT_EQ(j["schema"], 1);
  EXPECT_EQ(j["available"], true);
  EXPECT_FALSE(j.contains("reason"));
  EXPECT_FALSE(j["device"].get<std::string>().empty());
  EXPECT_TRUE(is_png(dir / "pictures" / j["colour_bar"].get<std::string>()));
  ASSERT_EQ(j["pictures"].size(), 6u);
  for (const auto& p : j["pictures"]) {
    SCOPED_TRACE(p.dump());
    EXPECT_FALSE(p.contains("error"));
    EXPECT_EQ(p["backend"], "cpu");
    EXPECT_EQ(p["level"], 3);
    EXPECT_GT(p["triangles"].get<long>(), 0);
    const fs::path file = dir / "pictures" / p["file"].get<std::string>();
    ASSERT_TRUE(is_png(file));
    const gpu::Image image = gpu::read_image(file.string());
    EXPECT_EQ(image.width, 160u);
    EXPECT_EQ(image.height, 120u);
    EXPECT_NE(image.pixel(80, 60), (std::array<uint8_t, 4>{255, 255, 255, 255}));  // the surface is in the middle
    EXPECT_EQ(p.contains("deviation_range"), p["kind"] == "deviation");
    if (p["kind"] == "deviation") {
      EXPECT_EQ(p["deviation_range"][0], 0.0);
      EXPECT_GE(p["deviation_range"][1].get<double>(), 0.0);
      // c-patches approximate the limit: visibly, but within their bound of 2% of the diagonal.
      if (p["scheme"] == "cpatch-2pass") {
        EXPECT_GT(p["deviation_range"][1].get<double>(), 1e-4);
        EXPECT_LT(p["deviation_range"][1].get<double>(), 0.02);
      }
    }
  }
  // The deviation picture is coloured, the shaded one is not.
  const gpu::Image shaded = gpu::read_image((dir / "pictures" / "cpatch-2pass_cube_shaded.png").string());
  const gpu::Image deviation = gpu::read_image((dir / "pictures" / "cpatch-2pass_cube_deviation.png").string());
  EXPECT_NE(shaded.rgba, deviation.rgba);
  const auto s = shaded.pixel(80, 60), d = deviation.pixel(80, 60);
  EXPECT_GT(s[0], s[2]);  // the warm material
  EXPECT_NE(d, s);
  EXPECT_FALSE(fs::exists(dir / "pictures" / "pictures.json.partial"));
}

TEST_F(WritePicturesOnDevice, AFailedPictureIsRecordedAndTheOthersDrawn) {
  const fs::path dir = fresh_dir("failure");
  PictureRequest request;
  request.schemes = {"cpatch-2pass", "fragments-loop"};
  request.meshes = {"icosphere"};
  request.level = 1;  // rate N = 1: c-patches decline it; depth 1 is fine for Loop
  request.width = 96, request.height = 64;
  const PictureManifest m = write_pictures(request, dir.string());
  ASSERT_TRUE(m.available) << m.reason;
  const nlohmann::json j = read_json(dir / "pictures" / "pictures.json");
  ASSERT_EQ(j["pictures"].size(), 4u);
  for (const auto& p : j["pictures"]) {
    SCOPED_TRACE(p.dump());
    if (p["scheme"] == "cpatch-2pass") {
      EXPECT_NE(p["error"].get<std::string>().find("below 2"), std::string::npos);
      EXPECT_FALSE(p.contains("file"));
    } else {
      EXPECT_FALSE(p.contains("error"));
      EXPECT_TRUE(is_png(dir / "pictures" / p["file"].get<std::string>()));
    }
  }
}

TEST_F(WritePicturesOnDevice, ASchemeRefusingTheMeshInPrepareLeavesANoteNotAFailure) {
  const fs::path dir = fresh_dir("refused");
  PictureRequest request;
  request.schemes = {"cpatch-2pass"};
  request.meshes = {"gim-ellipsoid-31"};  // passes acceptance; c-patches refuse its valence-2 vertices
  request.level = 3;
  request.width = 64, request.height = 48;
  const PictureManifest m = write_pictures(request, dir.string());
  EXPECT_TRUE(m.pictures.empty());
  ASSERT_EQ(m.notes.size(), 1u);
  EXPECT_NE(m.notes[0].find("valence 2"), std::string::npos) << m.notes[0];
  EXPECT_EQ(read_json(dir / "pictures" / "pictures.json")["pictures"].size(), 0u);
}

}  // namespace
}  // namespace sdb::pictures
